-- expect line 5: foreign.h5' exists and is not an HDF5 file
-- A result file named like an existing file that is not HDF5 (here a tire property file
-- the deck wrote itself): tirefe replaces only files of the kind it writes.
tirefe.write_tire{ file = "foreign.h5", parameters = require("tires.145SR12") }
tirefe.model{}:output{ file = "foreign.h5" }
