-- expect line 8: the tire touches the road through its tread rubber: give tread_layer_radial_stiffness and tread_layer_circumferential_stiffness
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.tread_layer_radial_stiffness = 0
tire.tread_layer_circumferential_stiffness = 0
model:tire(tire)
model:surface{ name = "road", type = "flat", point = { 0, -0.3 } }
model:tire_contact{ surface = "road", friction = 0.8 }
