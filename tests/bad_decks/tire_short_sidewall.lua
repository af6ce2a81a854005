-- expect line 6: tire parameter 'sidewall_length' must exceed the rim-to-tread distance
-- The sidewall cord is shorter than the rim-to-tread height: no arch exists.
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.sidewall_length = 0.10
model:tire(tire)
