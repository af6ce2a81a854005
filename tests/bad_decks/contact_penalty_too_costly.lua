-- expect line 10: scaling the tangential penalty from the structure at 3000 nodes of a model of 9003 DOFs would take 412 MiB of unit loads, more than the 256 MiB allowed; give tangential_penalty
-- The tangential penalty scaled from the structure solves for a dense column of unit loads
-- per contact node and direction: 3000 tread nodes would take 412 MiB (8000 take 3 GB and
-- minutes). It is refused before the memory goes.
local model = tirefe.model{ title = "costly contact penalty" }
local parameters = require("tires.145SR12")
parameters.elements = 3000
local tire = model:tire(parameters)
model:surface{ name = "road", type = "flat", point = { 0, -0.3 } }
model:contact{ surface = "road", set = tire.tread_set }
