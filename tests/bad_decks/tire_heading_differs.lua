-- expect line 8: this model's tires head +x: give every tire heading = "+x" (one result file states one heading)
local model = tirefe.model{}
local tp = require("tires.145SR12")
tp.elements = 12
model:tire(tp)
tp.heading, tp.name, tp.x = "-x", "second", 1.0
-- A second tire of the same model heading the other way.
model:tire(tp)
