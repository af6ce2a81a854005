-- expect line 5: no tire named 'front' in this model (it has 'tire')
local model = tirefe.model{}
model:tire(require("tires.145SR12"))
model:surface{ name = "road", type = "flat", point = { 0, -0.3 } }
model:tire_contact{ surface = "road", tire = "front" }
