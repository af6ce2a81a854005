-- A quarter car on the FE 145 SR-12 tire: settling to its static ride height on a
-- still road, then rolling at 18 km/h over a pothole. Checks against independent
-- references: the static jounce (weight - preload) / k_s and the tire load m g of the
-- first run, and the wheel-hop frequency of the second run against the two-mass
-- system linearised with the tire's own quasi-static stiffness. This deck checks itself.
--
--   tirefe inputs/quarter_car.lua [speed_kmh=18] [depth=0.02] [dt=1e-3]

local p = tirefe.parameters{
  speed_kmh = { 18.0, "road speed", unit = "km/h" },
  depth = { 0.02, "pothole depth", unit = "m" },
  length = { 0.3, "pothole length", unit = "m" },
  dt = { 1e-3, "time step", unit = "s" },
  body = { 300.0, "body mass of the quarter car", unit = "kg" },
  carrier = { 30.0, "wheel carrier mass", unit = "kg" },
  k_s = { 2.0e4, "suspension spring rate", unit = "N/m" },
  mu = { 0.9, "tire-road friction coefficient" },
}
local g = 9.81
local tp = require("tires.145SR12")
local tire_on_road = require("tire_on_road")
local press = require("press")

-- A tire model: inflated on a held hub, a road touching its lowest point, contact.
-- 'road' gets the road level and returns the surface arguments.
local function tire_model(title, road)
  local model = tirefe.model{ title = title }
  local tire, level = tire_on_road.inflated(model, tp)
  local surface = road(level)
  surface.name = "road"
  model:surface(surface)
  model:tire_contact{ surface = "road", friction = p.mu }
  return model, tire
end

local function corner(model, tire, preload, damping)
  return { name = "quarter", model = model, spindle = tire.spindle, mass = p.carrier, spring_rate = p.k_s,
           preload = preload, damping = damping, bumper_gap = 0.05, bumper_stiffness = 1e7,
           fore_aft_stiffness = 1e5, fore_aft_damping = 1e3 }
end

-- 1. Static ride height: critically damped, spring preload 0.8 of the body weight.
local still, still_tire = tire_model("quarter car settling", function(level)
  return { type = "flat", point = {0, level} }
end)
press.path(still, still_tire.spindle, "press"):move_to(0.015, 4, 0.25)  -- quasi-static, in 1 s
still:integrator{ type = "hht", alpha = -0.05 }
local settle = tirefe.vehicle{ body = { mass = p.body },
  corners = { corner(still, still_tire, 0.8 * p.body * g, 2 * math.sqrt(p.k_s * p.body)) },
  duration = 2.5, dt = 2e-3 }
local n = #settle.time
tirefe.check{ name = "static jounce = (weight - preload) / k_s [m]", value = settle.corners[1].jounce[n],
              expected = 0.2 * p.body * g / p.k_s, relative = 1e-3 }
tirefe.check{ name = "static tire load = total weight [N]", value = settle.corners[1].fz[n],
              expected = (p.body + p.carrier) * g, relative = 1e-3 }

-- 2. Rolling over the pothole, lightly damped.
local v = p.speed_kmh / 3.6
local start, ramp = 4.0, 0.3             -- the road starts after inflation and two presses
local ahead = 0.5 * v * ramp + v * 0.3   -- the pothole reaches the tire 0.3 s after the ramp
local rolling, tire = tire_model("quarter car over a pothole", function(level)
  return { type = "profile", pothole = {ahead, p.length, p.depth}, level = level, edge_radius = 0.01,
           speed = -v, ramp_time = ramp, start_time = start }
end)
-- Pressed quasi-statically to 10 and 20 mm (1 s each), then to the static deflection
-- that the secant stiffness between them gives.
local path = press.path(rolling, tire.spindle, "press")
local f1 = path:move_to(0.010, 4, 0.25):load()
local f2 = path:move_to(0.020, 4, 0.25):load()
local k_t = (f2 - f1) / 0.010             -- quasi-static vertical tire stiffness [N/m]
local weight = (p.body + p.carrier) * g
path:move_to(0.010 + (weight - f1) / k_t, 4, 0.25)
rolling:integrator{ type = "hht", alpha = -0.05 }
rolling:history{ name = "spindle_fx", node = tire.spindle, quantity = "spindle_force", component = "fx" }
rolling:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force", component = "fz" }
local run = tirefe.vehicle{ body = { mass = p.body }, corners = { corner(rolling, tire, p.body * g, 300) },
                            duration = 1.0, dt = p.dt }
print(string.format("quarter car: %d steps, %.2f corrector iterations/step, %.2f tire Newton iterations/solve, "
                    .. "%d cuts, wall %.2f s", run.steps, run.corrector_iterations / run.steps,
                    run.tire_newton_iterations / run.tire_solves, run.cuts, run.wall_time))

-- Wheel hop after the pothole: the mean period between maxima of the wheel's height.
local t_exit = start + ramp + 0.3 + p.length / v + 0.02
local peaks, z = {}, run.corners[1].wheel_z
for i = 2, #z - 1 do
  if run.time[i] > t_exit and z[i] > z[i - 1] and z[i] >= z[i + 1] then peaks[#peaks + 1] = run.time[i] end
end
local measured = (#peaks - 1) / (peaks[#peaks] - peaks[1])
-- Two-mass system: m_b on k_s, m_u = carrier + rim + belt (the belt ring moves with the hub at the hop
-- frequency, far below its own modes) on k_t; the higher eigenfrequency.
local m_b, m_u = p.body, p.carrier + tp.rim_mass + tp.tread_mass_per_length * math.pi * tp.outer_diameter
local a, b, c = m_b * m_u, -(p.k_s * m_u + (p.k_s + k_t) * m_b), p.k_s * k_t
local expected = math.sqrt((-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)) / (2 * math.pi)
print(string.format("k_t = %.0f N/m, wheel hop %.2f Hz (%d peaks), linear two-mass %.2f Hz, "
                    .. "sqrt((k_s + k_t) / m_u) / 2 pi = %.2f Hz", k_t, measured, #peaks, expected,
                    math.sqrt((p.k_s + k_t) / m_u) / (2 * math.pi)))
tirefe.check{ name = "wheel-hop frequency [Hz]", value = measured, expected = expected, relative = 0.05 }
