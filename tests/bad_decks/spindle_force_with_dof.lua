-- expect line 6: quantity "spindle_force" is in the tire's wheel axes: leave out 'dof' and give component
local model = tirefe.model{}
local tp = require("tires.145SR12")
tp.elements = 12
local tire = model:tire(tp)
model:history{ name = "spindle_fz", node = tire.spindle, dof = "uy", quantity = "spindle_force" }
