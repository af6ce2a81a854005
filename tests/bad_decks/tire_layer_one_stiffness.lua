-- expect line 5: tire parameter 'tread_layer_radial_stiffness' must be positive when the tread layer is on
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.tread_layer_radial_stiffness = 0
model:tire(tire)
