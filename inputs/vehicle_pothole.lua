-- The paper's vehicle experiment (docs/model.md section 7, its section 3.2): a mid-size car
-- on four FE 145 SR-12 tires at 0.243 MPa. Protocol, 9 s: 1 s quasi-static inflation
-- (here followed by another quasi-static second pressing each tire to its static corner
-- load, so the dynamic part runs from t = 2 s to 10 s); 1 s dynamic settling; the ground under
-- the car accelerates at a constant rate from 0 to 48 km/h over 5 s (the tires roll
-- freely, no drive torque); 2 s at 48 km/h, during which the LEFT wheels cross a
-- chuckhole 760 mm long and 100 mm deep ('lead' = 1 s into the cruise) while the right side stays
-- flat. Each corner's tire writes vehicle_pothole_<corner>.h5 with its spindle forces
-- and the body motions; the left-front and left-rear Fx, Fz around the pothole and
-- their spectra (wheel hop ~10 Hz; the first vertical tire mode ~90 Hz) are plotted by
--   /usr/bin/python3 post/plot_vehicle.py 8.9 10 results/vehicle_pothole_LF.h5 results/vehicle_pothole_LR.h5
-- Its run time is in docs/performance.md. The deck checks itself once the left wheels
-- have crossed: the weight and its split, the strike times.
--
--   tirefe inputs/vehicle_pothole.lua [dt=5e-4] [dt_pothole=2e-4] [dt_max=2e-3] [settle=1] [ramp=5]
--                                     [cruise=2] [lead=1] [depth=0.1] [threads=1]
--   mpirun -np 4 build/tirefe-mpi inputs/vehicle_pothole.lua      (the tires as MPI ranks)
--
-- The car: a mid-size sedan of ~1300 kg (curb mass, sprung 1160 kg) with a 2.7 m
-- wheelbase (centre of mass 1.1 m behind the front axle) and a 1.5 m track; pitch and
-- roll inertias from the usual radii of gyration (~1.2 x half the wheelbase, ~0.4 x
-- the track); ride frequencies 1.2 Hz front and 1.4 Hz rear and about 30% of critical
-- damping, with rebound twice as stiff as compression; jounce bumpers 60 mm from the
-- static position; 35 kg carriers (knuckle, brake, hub, half of the links), the
-- tire's rim and belt adding 12 kg. Typical values of the class (T. D. Gillespie,
-- Fundamentals of Vehicle Dynamics, SAE 1992, chapters 5-6); the paper's own
-- multibody model is not published.

local p = tirefe.parameters{
  tire = { "tires.145SR12", "tire parameter set in lua/tires/ (tires.145SR12_tread_layer: the calibrated tire)" },
  elements = { 100, "wedges around each tire" },
  dt = { 5e-4, "time step", unit = "s" },
  dt_pothole = { 2e-4, "time step while a wheel crosses the chuckhole", unit = "s" },
  dt_max = { 2e-3, "largest time step: settling, and the ramp while the road is slow (dt grows as 1 / speed)",
             unit = "s" },
  settle = { 1.0, "settling on the still road after inflation and pressing", unit = "s" },
  ramp = { 5.0, "the road's speed-up from rest", unit = "s" },
  cruise = { 2.0, "at speed after the ramp", unit = "s" },
  lead = { 1.0, "time at speed before the chuckhole reaches the front wheel", unit = "s" },
  depth = { 0.10, "chuckhole depth", unit = "m" },
  length = { 0.76, "chuckhole length", unit = "m" },
  speed_kmh = { 48.0, "road speed", unit = "km/h" },
  mu = { 0.9, "tire-road friction coefficient" },
  threads = { 1, "1: the tires solved on threads, 0: one after another" },
  newton_tolerance = { 1e-6, "tire Newton, on |R| / R_ref: spindle forces to ~5 mN" },
  newton_budget = { 0, "tire step budget: Newton iterations after which a solve within 1e-4 is taken (0: none)" },
  vehicle_tolerance = { 1e-4, "vehicle corrector, on |r|_inf / total weight (~1.3 N)" },
  predictor = { "zero_acceleration", "the tires' HHT predictor" },
}
local g = 9.81
local tp = require(p.tire)
local series = require("series")
tp.pressure = 0.243e6
tp.elements = p.elements

local wheelbase, a, track = 2.7, 1.1, 1.5
local sprung = 1160.0
local body = { mass = sprung, pitch_inertia = sprung * (1.2 * wheelbase / 2)^2,
               roll_inertia = sprung * (0.4 * track)^2 }
local carrier = 35.0
local v = p.speed_kmh / 3.6
local start = 2.0 + p.settle                         -- inflation 1 s, press 1 s, settling
tirefe.progress{ end_time = start + p.ramp + p.cruise }
local ahead = 0.5 * v * p.ramp + v * p.lead          -- the chuckhole reaches the front wheel 'lead' into the cruise

local corners = {}
for _, c in ipairs({ { name = "LF", x = a, y = track / 2, pothole = true },
                     { name = "RF", x = a, y = -track / 2, pothole = false },
                     { name = "LR", x = a - wheelbase, y = track / 2, pothole = true },
                     { name = "RR", x = a - wheelbase, y = -track / 2, pothole = false } }) do
  local front = c.x > 0
  local load = sprung * g * (front and (wheelbase - a) or a) / wheelbase / 2     -- static sprung corner load [N]
  local f_ride = front and 1.2 or 1.4
  local k_s = (2 * math.pi * f_ride)^2 * load / g
  local c_crit = 2 * math.sqrt(k_s * load / g)

  local model = tirefe.model{ title = "vehicle pothole, " .. c.name .. " tire" }
  model:output{ file = "vehicle_pothole_" .. c.name .. ".h5" }
  local tire, level = require("tire_on_road").inflated(model, tp)
  if c.pothole then
    -- Each tire stands at its own origin: the rear one meets the chuckhole a wheelbase later.
    model:surface{ name = "road", type = "profile", pothole = {ahead + a - c.x, p.length, p.depth}, level = level,
                   edge_radius = 0.02, speed = -v, ramp_time = p.ramp, start_time = start }
  else
    model:surface{ name = "road", type = "flat", point = {0, level}, speed = -v, ramp_time = p.ramp,
                   start_time = start }
  end
  model:tire_contact{ surface = "road", friction = p.mu, history = "patch" }
  -- Pressed to the static corner load: the deflection from the tire's secant stiffness
  -- between 10 and 20 mm (the press of the design position; settling does the rest).
  local weight = load + carrier * g
  local path = require("press").path(model, tire.spindle, "press")
  local f1 = path:move_to(0.010, 2, 0.25):load()
  local f2 = path:move_to(0.020, 1, 0.25):load()
  path:move_to(0.010 + (weight - f1) / ((f2 - f1) / 0.010), 1, 0.25)
  model:integrator{ type = "hht", alpha = -0.05, predictor = p.predictor }
  -- The contact patch's nodes land on the road with accelerations that jump from step to
  -- step at speed: starting Newton from a_{n+1} = 0 rather than a_n saves a third of the
  -- iterations and nearly all the step cuts (docs/vehicle.md).
  model:newton{ tolerance = p.newton_tolerance, budget_iterations = p.newton_budget }
  model:history{ name = "spindle_fx", node = tire.spindle, quantity = "spindle_force", component = "fx" }
  model:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force", component = "fz" }
  corners[#corners + 1] = {
    name = c.name, model = model, spindle = tire.spindle, x = c.x, y = c.y, mass = carrier,
    spring = { {-0.10, load - 0.10 * k_s}, {0, load}, {0.04, load + 0.04 * k_s}, {0.08, load + 0.08 * 1.6 * k_s} },
    damper = { {-1.0, -0.3 * c_crit * 2 / 1.5}, {0, 0}, {1.0, 0.3 * c_crit / 1.5} },  -- rebound 2 x compression
    bumper_gap = 0.06, bumper_stiffness = 2e7, fore_aft_stiffness = 3e5, fore_aft_damping = 3e3 }
end

-- The step while the wheels cross the chuckhole (dt_pothole; docs/vehicle.md: its edges' strikes).
local front_crossing = start + p.ramp + p.lead
local rear_crossing = front_crossing + wheelbase / v
-- Before the cruise, steps in which the road travels as far as in dt at full speed, up to
-- dt_max (never below dt): settling on the still road and the slow part of the ramp take
-- longer steps, in windows of a tenth of a second, the road's speed taken from its own
-- motion (tirefe.spin_up) at each window's end.
local windows = { { front_crossing - 0.02, rear_crossing + (p.length + 0.3) / v, p.dt_pothole } }
local longest = math.max(p.dt, p.dt_max)
if p.settle > 0 then windows[#windows + 1] = { 2.0, start, longest } end
local pieces = math.ceil(p.ramp / 0.1)
for k = 1, pieces do
  local from, to = start + (k - 1) * p.ramp / pieces, start + k * p.ramp / pieces
  local _, speed = tirefe.spin_up{ rate = v, ramp_time = p.ramp, start_time = start, time = to }
  windows[#windows + 1] = { from, to, math.max(p.dt, math.min(longest, p.dt * v / speed)) }
end
local run = tirefe.vehicle{ body = body, corners = corners, duration = p.settle + p.ramp + p.cruise, dt = p.dt,
                            step_windows = windows,
                            threads = p.threads == 1,
                            tolerance = p.vehicle_tolerance }
print(string.format("vehicle: %d steps, %.2f corrector iterations/step, %.2f tire Newton iterations/solve, "
                    .. "%d cuts, %d backtracks, wall %.1f s for %.1f s simulated", run.steps,
                    run.corrector_iterations / run.steps, run.tire_newton_iterations / run.tire_solves, run.cuts,
                    run.backtracks, run.wall_time, p.settle + p.ramp + p.cruise))
-- Loads before the chuckhole and each wheel's crossing, from every step (fx, fz: ISO 8855
-- wheel axes, heading +x), raw and low-passed at 200 Hz without phase lag (lua/strike.lua).
-- A left wheel's strike on the far edge is read where its load rises back through the
-- static load after it dropped into the chuckhole (below half of it); its tire's energy
-- balance and contact force over the strike come from the tire's own history.
local strike_reader = require("strike")
local function sample_before(values, time)
  local value = values[1]
  for i = 1, #run.time do
    if run.time[i] <= time then value = values[i] end
  end
  return value
end
local static, strikes, total = {}, {}, 0
for index, name in ipairs({ "LF", "RF", "LR", "RR" }) do
  local corner = run.corners[index]
  static[index] = sample_before(corner.fz, front_crossing - 0.02)
  total = total + static[index]
  local crossing = index <= 2 and front_crossing or rear_crossing
  local from, to = crossing - 0.02, math.min(crossing + (p.length + 0.3) / v, run.time[#run.time])
  if to > from + 0.01 then
    strikes[index] = strike_reader.read{ time = run.time, fx = corner.fx, fz = corner.fz, model = corners[index].model,
                                         from = from, to = to, static = static[index], bandwidth = 200,
                                         step = p.dt_pothole }
  end
  local s = strikes[index]
  local after = "the run ends before the chuckhole"
  if s then
    -- The readings in the corner's result file, /results (the convergence study reads them).
    for key, unit in pairs({ time = "s", fz_peak = "N", fx_low = "N", fx_high = "N", fz_peak_filtered = "N",
                             fx_low_filtered = "N", fx_high_filtered = "N", surface_work = "J",
                             energy_error = "J", step_error = "J" }) do
      if s[key] then corners[index].model:result{ name = "strike_" .. key, value = s[key], unit = unit } end
    end
    if s.contact_jump then corners[index].model:result{ name = "strike_contact_jump", value = s.contact_jump } end
    after = string.format("%s, peak %.0f N (200 Hz: %.0f N); Fx %.0f to %.0f N (200 Hz: %.0f to %.0f N)",
                          s.time and string.format("strike at t = %.4f s", s.time) or "no strike", s.fz_peak,
                          s.fz_peak_filtered, s.fx_low, s.fx_high, s.fx_low_filtered, s.fx_high_filtered)
  end
  print(string.format("%s spindle: Fz before the chuckhole %.0f N, %s", name, static[index], after))
  if s and s.surface_work then
    print(string.format("   the strike's contact %.4f-%.4f s: the road's work %.1f J, the balance's error %.2f J "
                        .. "(largest in a step %.3f J); contact force's largest step change %.0f %% of its peak",
                        s.contact_from, s.contact_to, s.surface_work, s.energy_error, s.step_error,
                        100 * s.contact_jump))
  end
end

-- Checks, for a run that reaches past the crossing: the tires carry the car's weight,
-- split front to rear by the centre of mass; the left wheels strike the chuckhole's far
-- edge a wheelbase apart in time, with the energy booked and the contact force continuous;
-- the right side stays near its load. For the deck's own protocol, the strikes' times and
-- peaks against the converged study of docs/vehicle.md (regression: this model's own
-- converged numbers, not a measurement).
if start + p.ramp + p.cruise < rear_crossing + (p.length + 0.3) / v then
  print("no checks: the run ends before the left wheels have crossed the chuckhole")
  return
end
local weight = (sprung + 4 * carrier) * g
tirefe.check{ name = "static tire loads = weight of the car [N]", value = total, expected = weight, relative = 0.01 }
tirefe.check{ name = "left-front static load [N]", value = static[1],
              expected = sprung * g * (wheelbase - a) / wheelbase / 2 + carrier * g, relative = 0.01 }
local LF, RF, LR = strikes[1], strikes[2], strikes[3]
if not (LF.time and LR.time) then error("a left wheel never dropped into the chuckhole and struck its far edge") end
tirefe.check{ name = "left-rear strike a wheelbase later [s]", value = LR.time - LF.time, expected = wheelbase / v,
              tolerance = 0.001 }
tirefe.check{ name = "right-front load stays within 10 % of its static load", value = RF.fz_peak / static[2],
              expected = 1, tolerance = 0.1 }
for _, wheel in ipairs({ { "left-front", LF }, { "left-rear", LR } }) do
  local name, s = wheel[1], wheel[2]
  if s.surface_work then
    tirefe.check{ name = "energy: " .. name .. " strike's balance error / the road's work on it",
                  value = s.energy_error / s.surface_work, expected = 0, tolerance = 0.02 }
    tirefe.check{ name = "energy: " .. name .. " strike's largest error in a step / the road's work",
                  value = s.step_error / s.surface_work, expected = 0, tolerance = 0.02 }
    tirefe.check{ name = "contact: " .. name .. " force's largest step change / its peak", value = s.contact_jump,
                  expected = 0, tolerance = 0.5 }
  end
end
-- The converged strikes (docs/vehicle.md, the study at dt_pothole = 50 us): time [s],
-- Fz peak, Fx low, Fx high, and the same low-passed [N], for each shipped tire.
local converged = {
  ["tires.145SR12"] = { LF = { 9.0482, 15260, -5185, 5006, 15153, -5113, 4788 },
                        LR = { 9.2514, 12241, -4199, 4239, 12155, -4176, 4091 } },
  ["tires.145SR12_tread_layer"] = { LF = { 9.0497, 14299, -4398, 2461, 14285, -4380, 2479 },
                                    LR = { 9.2527, 11680, -3036, 2603, 11661, -3049, 2551 } },
}
local defaults = { elements = 100, dt = 5e-4, dt_max = 2e-3, settle = 1.0, ramp = 5.0, cruise = 2.0, lead = 1.0,
                   depth = 0.10, length = 0.76, speed_kmh = 48.0, mu = 0.9 }
local protocol = converged[p.tire] ~= nil
for key, value in pairs(defaults) do protocol = protocol and math.abs(p[key] - value) <= 1e-9 * math.abs(value) end
if protocol then
  for _, wheel in ipairs({ { "left-front", LF, "LF" }, { "left-rear", LR, "LR" } }) do
    local name, s, c = wheel[1], wheel[2], converged[p.tire][wheel[3]]
    tirefe.check{ name = "regression: " .. name .. " strike vs converged [s]", value = s.time, expected = c[1],
                  tolerance = 0.002 }
    local readings = { { "Fz peak", s.fz_peak, c[2] }, { "Fx low", s.fx_low, c[3] }, { "Fx high", s.fx_high, c[4] },
                       { "Fz peak, 200 Hz", s.fz_peak_filtered, c[5] }, { "Fx low, 200 Hz", s.fx_low_filtered, c[6] },
                       { "Fx high, 200 Hz", s.fx_high_filtered, c[7] } }
    for _, r in ipairs(readings) do
      tirefe.check{ name = "regression: " .. name .. " " .. r[1] .. " vs converged [N]", value = r[2], expected = r[3],
                    relative = 0.03 }
    end
  end
end
