-- expect line 5: key 'heading' must be one of +x, -x (got 'forward')
local model = tirefe.model{}
local tp = require("tires.145SR12")
tp.elements, tp.heading = 12, "forward"
model:tire(tp)
