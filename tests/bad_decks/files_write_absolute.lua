-- expect line 4: '/tmp/tirefe_escape.h5' lies outside the output folder
-- A result file given an absolute path outside the output folder.
local model = tirefe.model{}
model:output{ file = "/tmp/tirefe_escape.h5" }
