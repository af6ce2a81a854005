-- expect line 6: tire parameter 'tread_layer_mass_per_length' must be positive when the tread layer is on
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.tread_layer_circumferential_stiffness = 7.6e6
tire.tread_layer_radial_stiffness = 4e7
model:tire(tire)
