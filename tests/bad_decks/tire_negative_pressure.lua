-- expect line 5: key 'pressure' must be non-negative (got -200000)
local model = tirefe.model{}
local tire = require("tires.145SR12")
tire.pressure = -0.2e6
model:tire(tire)
