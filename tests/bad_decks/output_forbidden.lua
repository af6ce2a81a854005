-- expect line 4: /proc/forbidden/x.h5
-- An output path that cannot be created.
local model = tirefe.model{}
model:output{ file = "/proc/forbidden/x.h5" }
