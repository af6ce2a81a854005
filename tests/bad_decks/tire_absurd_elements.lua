-- expect line 6: key 'elements' must be an integer from 1 to 100000 (got number 20000000)
-- 20 million wedges would run for minutes into an out-of-memory failure.
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.elements = 20000000
model:tire(tire)
