-- expect line 6: key 'elements' must be an integer from 1 to 100000 (got number 4294967320)
-- 2^32 + 24 would wrap to 24 elements in a C++ int.
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.elements = 2^32 + 24
model:tire(tire)
