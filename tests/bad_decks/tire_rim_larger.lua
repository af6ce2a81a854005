-- expect line 5: tire parameter 'rim_diameter' must be smaller than outer_diameter
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.rim_diameter = 0.6
model:tire(tire)
