-- expect line 5: tire parameter 'elements' must be at least 8
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.elements = 1
model:tire(tire)
