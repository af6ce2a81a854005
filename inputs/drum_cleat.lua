-- Drum-cleat test (Mousseau, Laursen, Lidberg, Taylor 1999, section 3.1; docs/drum_cleat.md).
--
-- A 145 SR-12 tire on a dead axle rolls on a 1.7 m drum carrying a cleat 25 mm high and
-- 660 mm long, friction 0.3. 0-1 s: inflation on a fixed hub; 1-2 s: pressed onto the drum
-- to the spindle load (quasi-static); 2-6 s: the drum spins up from rest to 51.3 km/h and
-- friction makes the tire roll; then the speed is held to 8 s. The cleat comes round every
-- pi D / v (0.375 s at full speed). The spindle forces, spin rate, drum angle, contact
-- totals and energies are written every step, the deformed tire every fields_interval.
-- The deck ends with a summary of the last two cleat passages at full speed (their peaks
-- depend on where the tread nodes meet the cleat): peak-to-peak spindle forces and the
-- ringing frequencies of Fx and Fz on top of the cleat and after it, each and together.
--
--   tirefe inputs/drum_cleat.lua [speed_kmh=51.3] [cleat_height=0.025] [integrator=newmark] ...
--
-- Axes: x to the right, y up; the tire sits on top of the drum; the drum turns clockwise,
-- so its top and the cleat move in +x under the tire, and the tire travels over the drum's
-- surface toward -x: its heading is -x. Spindle forces and the spin rate are in ISO 8855
-- wheel axes (docs/output.md, "Axes and signs"): Fz > 0 the load, Fx < 0 where the cleat
-- retards the wheel, spin rate > 0 rolling forward.

-- Each parameter: { default, "meaning", unit = "..." } (tirefe --list-parameters lists them).
local p = tirefe.parameters{
  tire = { "tires.145SR12_tread_layer", "parameter set in lua/tires/ (tires.145SR12: the paper's model)" },
  elements = { 100, "wedges around the tire" },
  rim_inertia = { 0.0, "rotary inertia of what turns with the tire (0: the tire set's)", unit = "kg m^2" },
  tread_shear_stiffness = { 0.0, "tread rubber's shear stiffness per length (0: the tire set's)", unit = "N/m^2" },
  tread_shear_damping = { -1.0, "tread rubber's shear dashpot per length (< 0: the tire set's)", unit = "N s/m^2" },
  pressure_kpa = { 208, "inflation pressure", unit = "kPa" },
  load = { 3800, "spindle load on the drum", unit = "N" },
  drum_diameter = { 1.7, "drum diameter", unit = "m" },
  cleat_height = { 0.025, "cleat height", unit = "m" },
  cleat_length = { 0.66, "cleat length along the drum surface", unit = "m" },
  cleat_edge_radius = { 0.005, "rounding of the cleat's top edges", unit = "m" },
  cleat_start_deg = { -90.0, "where the cleat's middle is at rest, from +x (-90: bottom)", unit = "deg" },
  friction = { 0.3, "Coulomb friction coefficient" },
  speed_kmh = { 51.3, "final drum surface speed", unit = "km/h" },
  spin_up_time = { 4.0, "spin-up of the drum from rest, from t = 2 s", unit = "s" },
  end_time = { 8.0, "end of the run", unit = "s" },
  integrator = { "hht", "hht or newmark" },
  newmark_gamma = { 0.5, "Newmark gamma, beta = (gamma + 1/2)^2 / 4 (0.5: average acceleration)" },
  newton_tolerance = { 1e-5, "Newton tolerance on the residual relative to the step's force level" },
  newton_budget = { 1, "a step budget: Newton iterations after which a step within 1e-4 is taken (0: none)" },
  alpha = { -0.1, "HHT alpha" },
  dt = { 5e-4, "time step at full speed away from the cleat", unit = "s" },
  dt_max = { 2e-3, "largest time step, during the spin-up (dt grows as 1 / speed)", unit = "s" },
  dt_cleat = { 2.5e-4, "time step through a full-speed passage and the one before: from 10 ms before the cleat until ring_time after it", unit = "s" },
  ring_time = { 0.15, "fine steps after the cleat left the tire (past the last ringing window)", unit = "s" },
  fields_interval = { 0.005, "time between deformed-shape frames", unit = "s" },
  output = { "drum_cleat.h5", "result file (in the output folder)" },
  views = { false, "make the frames' views for the XDMF index during the run (false: tirefe --views FILE after it)" },
  check = { false, "the deck's self-checks (the test suite's short run sets it)" },
}
tirefe.progress{ end_time = p.end_time }

local guard = require("guard")
guard.positive(p, { "pressure_kpa", "load", "drum_diameter", "cleat_length", "speed_kmh", "spin_up_time", "dt",
                    "dt_max", "dt_cleat", "ring_time", "fields_interval" })
guard.non_negative(p, { "cleat_height", "rim_inertia", "tread_shear_stiffness" })
if p.end_time <= 2.0 + p.dt then error("parameter end_time must be later than the 2 s of inflation and pressing") end

-- The rig (lua/drum.lua): the drum's turn, the cleat's passages under the tire and the
-- time steps, fine from shortly before a passage at full speed (and the one before them)
-- until ring_time after it, elsewhere steps in which a tread node travels the same
-- distance at any speed (up to dt_max), the slow passages of the spin-up included.
local rig = require("drum").rig{ diameter = p.drum_diameter, speed = p.speed_kmh / 3.6, start = 2.0,
                                 spin_up_time = p.spin_up_time }
local cleat = { cleat_angle = math.rad(p.cleat_start_deg), cleat_length = p.cleat_length, end_time = p.end_time }
local passages = rig:passages(cleat)
rig:require_full_speed_passage(cleat, p.ring_time)  -- the summary reads one
local time_step = rig:time_step{ passages = passages, dt = p.dt, dt_max = p.dt_max, dt_cleat = p.dt_cleat,
                                 ring_time = p.ring_time }

-- Model: the tire on top of the drum, touching it at rest.
local model = tirefe.model{ title = "drum-cleat test, " .. p.tire }
local tire_parameters = require(p.tire)
tire_parameters.elements = p.elements
if p.rim_inertia > 0 then tire_parameters.rim_rotary_inertia = p.rim_inertia end
if p.tread_shear_stiffness > 0 then tire_parameters.tread_layer_circumferential_stiffness = p.tread_shear_stiffness end
if p.tread_shear_damping >= 0 then tire_parameters.tread_layer_circumferential_damping = p.tread_shear_damping end
tire_parameters.pressure = p.pressure_kpa * 1e3
tire_parameters.pressure_load_function = "inflation"
tire_parameters.y = rig.radius + tire_parameters.outer_diameter / 2
model:load_function{ name = "inflation", points = { { 0, 0 }, { 1, 1 }, { 1e9, 1 } } }
tire_parameters.heading = "-x"  -- travelling over the drum's top, which moves to +x
local tire = model:tire(tire_parameters)

-- Spindle: held during inflation and pressing, its height on the press path (lua/press.lua);
-- the depth pressed to is then kept (the dead axle).
model:fix{ node = tire.spindle, dofs = { "ux", "rz" } }
local press = require("press").path(model, tire.spindle, "press")

model:output{ file = p.output, fields_interval = p.fields_interval, views = p.views }
model:history{ name = "spindle_fx", node = tire.spindle, quantity = "spindle_force", component = "fx" }
model:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force", component = "fz" }
model:history{ name = "spin_rate", node = tire.spindle, quantity = "spin_rate" }
model:history{ name = "spindle_height", node = tire.spindle, dof = "uy" }
model:history{ name = "spindle_turn", node = tire.spindle, dof = "rz" }

-- 0-1 s: inflation, then the drum under the tire: the tread touches it through its
-- rubber (docs/contact.md, Tread contact).
model:solve{ to = 1.0, dt = 0.25 }
model:surface{ name = "drum", type = "drum", diameter = p.drum_diameter, cleat_height = p.cleat_height,
               cleat_length = p.cleat_length, cleat_angle = cleat.cleat_angle, edge_radius = p.cleat_edge_radius,
               speed = -rig.omega, ramp_time = p.spin_up_time, ramp = rig.ramp, start_time = rig.start }
model:tire_contact{ surface = "drum", friction = p.friction, history = "drum", output_every = 20 }

-- 1-2 s: press. Five steps toward a first guess of the deflection, then secant steps on the
-- measured force-deflection curve until the spindle carries the load to 0.1 %.
local loaded_deflection = press:to_load{ load = p.load }
model:solve{ to = rig.start, dt = 0.1 }
local spindle_fz_at_start = press:load()
print(string.format("pressed: deflection %.2f mm for %.1f N, contact patch %.1f mm", loaded_deflection * 1e3,
                    press:load(), model:contact_value{ name = "contact_drum", quantity = "patch_length" } * 1e3))

-- 2-8 s: the drum spins up; the spindle turns freely on the dead axle.
model:release{ node = tire.spindle, dofs = { "rz" } }
model:newton{ tolerance = p.newton_tolerance, budget_iterations = p.newton_budget }
-- A step cut to a thousandth of dt means the solution is falling apart: stop with a message.
model:step_control{ min_dt = p.dt_cleat / 1024, max_cuts = 10 }
local stepping = require("stepping")
stepping.integrator(model, { type = p.integrator, alpha = p.alpha, gamma = p.newmark_gamma })
local _, totals = stepping.run(model, { to = p.end_time, time_step = time_step })
stepping.report(model, totals, "dynamic")
-- The whole run's spindle channels, one value per step, as the result file holds them.
local function history(name) return model:history_values{ name = name } end
local record = { time = history("time"), fx = history("spindle_fx"), fz = history("spindle_fz"),
                 spin = history("spin_rate"), turn = history("spindle_turn") }

-- Summary of the last two passages at full speed with their ringing recorded
-- (lua/cleat_summary.lua): peak-to-peak forces, ringing frequencies, the impacts' period,
-- the rolling radius before the last.
local cleat_ringing = require("cleat_ringing")
local summary = require("cleat_summary").report{ model = model, rig = rig, passages = passages, record = record,
  ring_time = p.ring_time, end_time = p.end_time, speed_kmh = p.speed_kmh, measured = cleat_ringing.measured(p),
  tread = tire.tread, unloaded_radius = tire_parameters.outer_diameter / 2, deflection = loaded_deflection,
  elements = p.elements }
if p.check then
  tirefe.check{ name = "pressed to the load [N]", value = spindle_fz_at_start, expected = p.load, tolerance = 1e-3 * p.load }
  tirefe.check{ name = "a full-speed cleat passage was run", value = summary.passage and 1 or 0, expected = 1,
                tolerance = 0 }
  tirefe.check{ name = "rolling radius = tread ring circumference / 2 pi [m]", value = summary.rolling_radius,
                expected = summary.belt_radius, tolerance = 2e-3 * summary.belt_radius }
  -- The energy balance of the dynamic run: what the scheme created or lost against what
  -- friction and the dashpots took (docs/dynamics.md), and the drum's contact force from
  -- step to step through the passages (docs/drum_cleat.md, Impact).
  local time, since = history("time"), nil
  for i, t in ipairs(time) do if not since and t >= rig.start then since = i end end
  local function grown(name) local v = history(name); return v[#v] - v[since] end
  local dissipated = grown("contact_dissipated") + grown("energy_damping")
  tirefe.check{ name = "energy: balance error / friction and damping's dissipation", value =
                grown("energy_balance_error") / dissipated, expected = 0, tolerance = 0.01 }
  local normal, peak, jump = history("drum_fy"), 0, 0
  for i = since + 1, #normal do
    peak = math.max(peak, math.abs(normal[i]))
    jump = math.max(jump, math.abs(normal[i] - normal[i - 1]))
  end
  tirefe.check{ name = "contact: the largest step-to-step change of the drum's force / its peak", value = jump / peak,
                expected = 0, tolerance = 0.1 }
  if p.tire == "tires.145SR12_tread_layer" and summary.measured then
    cleat_ringing.check_calibrated(summary.ringing, summary.measured)  -- against the measured ringing
    if summary.before then cleat_ringing.check_calibrated(summary.before.ringing, summary.measured, "passage before") end
  end
end

return { summary = summary, passages = passages, record = record }
