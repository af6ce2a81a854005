-- expect line 5: /proc/forbidden/x.h5
-- args: --allow-write /proc
-- An output path that cannot be created (in a folder the command line allows).
local model = tirefe.model{}
model:output{ file = "/proc/forbidden/x.h5" }
