-- expect line 5: /dev/null/results.h5
-- args: --allow-write /dev/null
-- An output path below a file, which cannot be a folder (allowed by the command line).
local model = tirefe.model{}
model:output{ file = "/dev/null/results.h5" }
