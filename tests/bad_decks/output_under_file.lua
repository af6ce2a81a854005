-- expect line 4: /dev/null/results.h5
-- An output path below a file, which cannot be a folder.
local model = tirefe.model{}
model:output{ file = "/dev/null/results.h5" }
