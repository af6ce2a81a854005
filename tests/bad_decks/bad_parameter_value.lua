-- expect line 3: must be a number like its default
-- args: speed_kmh=fast
local p = tirefe.parameters{ speed_kmh = 51.3 }
