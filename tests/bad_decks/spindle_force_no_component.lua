-- expect line 6: quantity "spindle_force" needs component = "fx", "fz" or "my"
local model = tirefe.model{}
local tp = require("tires.145SR12")
tp.elements = 12
local tire = model:tire(tp)
model:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force" }
