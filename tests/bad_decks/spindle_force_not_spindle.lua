-- expect line 6: node 2 is no tire's spindle: give node = tire.spindle
local model = tirefe.model{}
local tp = require("tires.145SR12")
tp.elements = 12
local tire = model:tire(tp)
model:history{ name = "spindle_fz", node = tire.tread[1], quantity = "spindle_force", component = "fz" }
