-- Restart test deck: a ring pressed onto a flat road that moves under it, with friction,
-- integrated with HHT-alpha. It writes an immediate checkpoint at t_mid, automatic ones
-- every 'every' steps and a final one; tests/test_restart.cpp restarts it from them.
local p = tirefe.parameters{ elements = 24, t_mid = 0.12, t_end = 0.3, dt = 2e-3, every = 40,
                              alpha = -0.1, with_contact = 1 }

local model = tirefe.model{ title = "Ring on a moving road (restart test)" }
local radius, centre_y = 0.3, 0.302
local ring = {}
for i = 0, p.elements - 1 do
  local angle = 2 * math.pi * i / p.elements - math.pi / 2   -- node 1 at the bottom
  ring[#ring + 1] = model:node{ x = radius * math.cos(angle), y = centre_y + radius * math.sin(angle) }
end
local top = ring[p.elements // 2 + 1]
model:node_set{ name = "ring", nodes = ring }
model:node_set{ name = "top", nodes = { top } }
model:section{ name = "tread", EA = 1e6, GA = 3e5, EI = 40, rhoA = 2.0, rhoI = 1e-3 }
model:beam{ section = "tread", nodes = ring, closed = true }
model:fix{ node = top, dofs = { "ux", "rz" } }
model:prescribe{ node = top, dof = "uy", value = -0.03 / p.t_end }   -- ramp: 0.03 m down at t_end

model:output{ file = "restart.h5", fields_every = 25 }
model:surface{ name = "road", type = "flat", speed = -2.0, ramp_time = 0.1 }
if p.with_contact == 1 then
  model:contact{ surface = "road", set = "ring", friction = 0.6, penalty = 2e6, tangential_penalty = 2e5,
                 history = "patch", output_every = 5 }
end

model:integrator{ type = "hht", alpha = p.alpha }
model:history{ name = "top_force", set = "top", dof = "uy", quantity = "reaction" }
model:checkpoint{ file = "auto.ckpt.h5", every_steps = p.every }

model:solve{ to = p.t_mid, dt = p.dt }
model:checkpoint{ file = "mid.ckpt.h5" }
model:solve{ to = p.t_end }
model:checkpoint{ file = "end.ckpt.h5" }
