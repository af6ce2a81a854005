-- expect line 5: missing required key 'k_gamma'
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.k_gamma = nil
model:tire(tire)
