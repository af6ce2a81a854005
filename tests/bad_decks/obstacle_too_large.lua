-- expect line 26: could not be solved
-- keeps: obstacle_too_large.h5 10
-- A ring held at its top rolls onto a wall taller than itself: once the wall reaches the
-- held node no step cut can keep the node out of it (min_dt bounds the cuts, else the
-- steps would shrink from step to step). The run stops with the step-failure
-- message; its result file keeps every step before.
local model = tirefe.model{ title = "obstacle too large" }
local ring = {}
for i = 0, 15 do
  local angle = 2 * math.pi * i / 16 - math.pi / 2
  ring[#ring + 1] = model:node{ x = 0.3 * math.cos(angle), y = 0.302 + 0.3 * math.sin(angle) }
end
local top = ring[9]
model:node_set{ name = "ring", nodes = ring }
model:section{ name = "tread", EA = 1e6, GA = 3e5, EI = 40, rhoA = 2.0, rhoI = 1e-3 }
model:beam{ section = "tread", nodes = ring, closed = true }
model:fix{ node = top }
model:output{ file = "obstacle_too_large.h5" }
model:surface{ name = "road", type = "profile", cleat = { 0.5, 0.3, 1.0 }, speed = -2.0 }
model:contact{ surface = "road", set = "ring", penalty = 2e6, tangential_penalty = 2e5,
               penetration_limit = 0.005 }
model:integrator{ type = "hht", alpha = -0.1 }
model:history{ name = "top_fx", node = top, dof = "ux", quantity = "reaction" }
model:step_control{ max_cuts = 4, min_dt = 1e-4 }
model:newton{ max_iterations = 12 }
model:solve{ to = 1.0, dt = 5e-3 }
