-- expect line 7: the spindle force needs a dynamic tire analysis (newmark, hht, wbz or generalized_alpha)
local model = tirefe.model{}
local tp = require("tires.145SR12")
tp.elements = 12
local tire = model:tire(tp)
model:fix{ node = tire.spindle }
model:spindle_force{ node = tire.spindle, x = 0, y = 0, dt = 1e-3 }
