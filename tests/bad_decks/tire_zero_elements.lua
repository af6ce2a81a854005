-- expect line 5: key 'elements' must be positive (got 0)
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.elements = 0
model:tire(tire)
