-- expect line 7: model 'tire' is busy in tirefe.vehicle
-- A tire's load function asking its model for anything while the vehicle steps the tire
-- is refused: the vehicle holds the tire in the middle of a step.
local model = tirefe.model{ title = "tire" }
local tire = model:tire(require("tires.145SR12"))
model:integrator{ type = "hht", alpha = -0.05 }
model:load_function{ name = "peek", fn = function(t) return model:time() end }
model:load{ node = tire.tread[1], fy = -1, load_function = "peek" }
tirefe.vehicle{ body = { mass = 300 },
                corners = { { model = model, spindle = tire.spindle, mass = 30, spring_rate = 2e4, damping = 1e3 } },
                duration = 0.01, dt = 1e-3, threads = false }
