-- The spindle force macro on the 145 SR-12 tire rolling on a flat road: inflated on a
-- held hub, pressed 20 mm onto the road, then the road starts moving (5 m/s) and the
-- tire, its spindle held by model:spindle_force with a free spin, rolls up to speed.
-- Checks: the Jacobian against central differences of the converged spindle force,
-- the vertical spindle force against the contact force (the tire's inertia is small in
-- steady rolling), and the rolling speed against the road speed. This deck checks itself.
--
--   tirefe inputs/spindle_force.lua [steps=150] [dt=1e-3] [speed=5]

local p = tirefe.parameters{
  steps = { 150, "rolling steps" },
  dt = { 1e-3, "time step", unit = "s" },
  speed = { 5.0, "road speed", unit = "m/s" },
  deflection = { 0.02, "spindle pressed onto the road by", unit = "m" },
  mu = { 0.8, "tire-road friction coefficient" },
}

local model = tirefe.model{ title = "spindle force of a rolling tire" }
local tp = require("tires.145SR12")
-- Inflated on a held hub; the road touches the inflated tire's lowest tread node.
local tire, level = require("tire_on_road").inflated(model, tp)
model:surface{ name = "road", type = "flat", point = {0, level}, speed = -p.speed, ramp_time = 0.05, start_time = 2.0 }
model:tire_contact{ surface = "road", friction = p.mu, history = "patch" }
require("press").path(model, tire.spindle, "press"):move_to(p.deflection, 4, 0.25)  -- from 1 to 2 s

model:integrator{ type = "hht", alpha = -0.05 }
model:step_control{ max_augmentations = 0 }  -- the Jacobian holds the step's contact multipliers
model:newton{ tolerance = 1e-12 }
model:history{ name = "spin_rate", node = tire.spindle, quantity = "spin_rate" }
local s
for _ = 1, p.steps do
  s = model:spindle_force{ node = tire.spindle, x = 0, y = -p.deflection, dt = p.dt, commit = true }
end

-- Central differences of the converged force w.r.t. the spindle position.
local h = 1e-7
local centre = model:spindle_force{ node = tire.spindle, x = 0, y = -p.deflection, dt = p.dt }
local worst, scale = 0, 0
local rim = tp.rim_mass / (0.25 * (1 + 0.05)^2 * p.dt^2)  -- m / (beta h^2): the rim's inertia in H
for j, d in ipairs({{h, 0}, {0, h}}) do
  local plus = model:spindle_force{ node = tire.spindle, x = d[1], y = -p.deflection + d[2], dt = p.dt }
  local minus = model:spindle_force{ node = tire.spindle, x = -d[1], y = -p.deflection - d[2], dt = p.dt }
  for i, f in ipairs({"fx", "fy"}) do
    local fd = (plus[f] - minus[f]) / (2 * h)
    worst = math.max(worst, math.abs(fd - centre.jacobian[i][j]))
    scale = math.max(scale, math.abs(centre.jacobian[i][j] - (i == j and rim or 0)))
  end
end
print(string.format("H_ss = [%.6e %.6e; %.6e %.6e] N/m, |H - FD| = %.3e N/m", centre.jacobian[1][1],
                    centre.jacobian[1][2], centre.jacobian[2][1], centre.jacobian[2][2], worst))
tirefe.check{ name = "H_ss vs central differences / tire stiffness", value = worst / scale, expected = 0,
              tolerance = 1e-5 }
local fy = model:contact_value{ name = "contact_road", quantity = "fy" }
tirefe.check{ name = "spindle force y vs contact force y", value = s.fy, expected = -fy, relative = 0.02 }
local omega = model:value{ node = tire.spindle, quantity = "spin_rate" }  -- heading +x: forward is positive
local rolling_radius = tp.outer_diameter / 2 - p.deflection / 3  -- a belt tire rolls close to its unloaded radius
tirefe.check{ name = "spin rate vs road speed / rolling radius [rad/s]", value = omega,
              expected = p.speed / rolling_radius, relative = 0.05 }
