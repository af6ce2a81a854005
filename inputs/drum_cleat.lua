-- Drum-cleat test (Mousseau, Laursen, Lidberg, Taylor 1999, section 3.1; docs/drum_cleat.md).
--
-- A 145 SR-12 tire on a dead axle rolls on a 1.7 m drum carrying a cleat 25 mm high and
-- 660 mm long, friction 0.3. 0-1 s: inflation on a fixed hub; 1-2 s: pressed onto the drum
-- to the spindle load (quasi-static); 2-6 s: the drum spins up from rest to 51.3 km/h and
-- friction makes the tire roll; then the speed is held to 8 s. The cleat comes round every
-- pi D / v (0.375 s at full speed). The spindle forces, spin rate, drum angle, contact
-- totals and energies are written every step, the deformed tire every fields_interval.
-- The deck ends with a summary of the last cleat passage at full speed: peak-to-peak
-- spindle forces and the ringing frequencies of Fx and Fz on top of the cleat and after it.
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
  pressure_kpa = { 208, "inflation pressure", unit = "kPa" },
  load = { 3800, "spindle load on the drum", unit = "N" },
  drum_diameter = { 1.7, "drum diameter", unit = "m" },
  cleat_height = { 0.025, "cleat height", unit = "m" },
  cleat_length = { 0.66, "cleat length along the drum surface", unit = "m" },
  cleat_edge_radius = { 0.005, "rounding of the cleat's top edges", unit = "m" },
  cleat_start_deg = { -90, "where the cleat's middle is at rest, from +x (-90: bottom)", unit = "deg" },
  friction = { 0.3, "Coulomb friction coefficient" },
  contact_penalty = { 2e7, "normal contact penalty (1.5 kN on a node penetrates 0.08 mm)", unit = "N/m" },
  tangential_factor = { 30, "tangential penalty / the structure's tangential stiffness at a contact node" },
  contact_tolerance = { 5e-4, "penetration left after the Uzawa updates", unit = "m" },
  multiplier_tolerance = { 1e3, "relative multiplier change asking for an update (1e3: only penetration does)" },
  speed_kmh = { 51.3, "final drum surface speed", unit = "km/h" },
  spin_up_time = { 4.0, "spin-up of the drum from rest, from t = 2 s", unit = "s" },
  end_time = { 8.0, "end of the run", unit = "s" },
  integrator = { "hht", "hht or newmark" },
  newmark_gamma = { 0.5, "Newmark gamma, beta = (gamma + 1/2)^2 / 4 (0.5: average acceleration)" },
  newton_tolerance = { 1e-5, "Newton tolerance on the residual relative to the step's force level" },
  alpha = { -0.1, "HHT alpha" },
  dt = { 5e-4, "time step at full speed away from the cleat", unit = "s" },
  dt_max = { 2e-3, "largest time step, during the spin-up (dt grows as 1 / speed)", unit = "s" },
  dt_cleat = { 2.5e-4, "time step from just before the cleat until ring_time after it", unit = "s" },
  ring_time = { 0.15, "fine steps after the cleat left the tire (past the last ringing window)", unit = "s" },
  fields_interval = { 0.005, "time between deformed-shape frames", unit = "s" },
  output = { "drum_cleat.h5", "result file (in the output folder)" },
  check = { false, "the deck's self-checks (the test suite's short run sets it)" },
}
tirefe.progress{ end_time = p.end_time }

local function require_positive(name)
  if not (p[name] > 0) then error(string.format("parameter %s = %g must be positive", name, p[name]), 2) end
end
for _, name in ipairs{ "pressure_kpa", "load", "drum_diameter", "cleat_length", "speed_kmh", "spin_up_time",
                       "dt", "dt_max", "dt_cleat", "ring_time", "fields_interval" } do
  require_positive(name)
end
if p.cleat_height < 0 then error("parameter cleat_height must not be negative") end
if p.end_time <= 2.0 + p.dt then error("parameter end_time must be later than the 2 s of inflation and pressing") end

local R = p.drum_diameter / 2
local speed = p.speed_kmh / 3.6                -- drum surface speed [m/s]
local omega = speed / R                         -- drum spin [rad/s]
local dynamic_start = 2.0

-- The drum's clockwise angle at time t, and its inverse.
local function drum_angle(t)
  local running = t - dynamic_start
  if running <= 0 then return 0 end
  local ramp = math.min(running, p.spin_up_time)
  return 0.5 * omega * ramp * ramp / p.spin_up_time + omega * math.max(running - p.spin_up_time, 0)
end
local function time_at_angle(angle)
  local ramp_angle = 0.5 * omega * p.spin_up_time
  if angle <= ramp_angle then return dynamic_start + math.sqrt(2 * angle * p.spin_up_time / omega) end
  return dynamic_start + p.spin_up_time + (angle - ramp_angle) / omega
end

local cleat_angle = math.rad(p.cleat_start_deg)
local cleat_half_angle = p.cleat_length / (2 * R)
if cleat_half_angle >= math.pi / 2 then error("parameter cleat_length is too long for the drum") end

-- Passages of the cleat under the tire: the times its leading edge and its trailing edge
-- pass the top of the drum (the middle of the contact patch).
local passages = {}
do
  local lead = (cleat_angle - cleat_half_angle) - math.pi / 2 -- clockwise turn that brings the leading edge to the top
  local trail = (cleat_angle + cleat_half_angle) - math.pi / 2
  while lead < 0 do lead, trail = lead + 2 * math.pi, trail + 2 * math.pi end
  while time_at_angle(lead) < p.end_time do
    passages[#passages + 1] = { on = time_at_angle(lead), off = time_at_angle(trail) }
    lead, trail = lead + 2 * math.pi, trail + 2 * math.pi
  end
  -- The summary reads a passage at full speed with its ringing: refuse a protocol that has none.
  local full_speed_lead = lead - 2 * math.pi * #passages
  while time_at_angle(full_speed_lead) < dynamic_start + p.spin_up_time do full_speed_lead = full_speed_lead + 2 * math.pi end
  local needed = time_at_angle(full_speed_lead + 2 * cleat_half_angle) + p.ring_time
  if needed > p.end_time + 1e-9 then
    error(string.format("parameter end_time = %g s ends before the first cleat passage at full speed has rung out: "
                        .. "give end_time >= %.3f s", p.end_time, needed), 0)
  end
end

-- Fine steps from shortly before a passage until ring_time after it; elsewhere steps in
-- which a tread node travels the same distance at any speed (up to dt_max).
local function near_cleat(t)
  for _, passage in ipairs(passages) do
    if t > passage.on - 0.01 and t < passage.off + p.ring_time then return true end
  end
  return false
end
local function drum_speed(t)
  return speed * math.min(math.max(t - dynamic_start, 0) / p.spin_up_time, 1)
end
local function time_step(t)
  if near_cleat(t) then return p.dt_cleat end
  return math.min(p.dt_max, p.dt * speed / math.max(drum_speed(t), 1e-9))
end

-- Model: the tire on top of the drum, touching it at rest.
local model = tirefe.model{ title = "drum-cleat test, " .. p.tire }
local tire_parameters = require(p.tire)
tire_parameters.elements = p.elements
tire_parameters.pressure = p.pressure_kpa * 1e3
tire_parameters.pressure_load_function = "inflation"
tire_parameters.y = R + tire_parameters.outer_diameter / 2
model:load_function{ name = "inflation", points = { { 0, 0 }, { 1, 1 }, { 1e9, 1 } } }
tire_parameters.heading = "-x"  -- travelling over the drum's top, which moves to +x
local tire = model:tire(tire_parameters)

-- Spindle: held during inflation and pressing. Its height follows the press path, a list
-- of (time, depth) points that the pressing phase extends until the spindle carries the
-- load; the last depth is then kept (the dead axle).
local press_path = { { 0.0, 0.0 } }
local function press_depth(t)
  for i = #press_path, 1, -1 do
    local t1, d1 = press_path[i][1], press_path[i][2]
    if t >= t1 then
      local following = press_path[i + 1]
      if not following then return d1 end
      return d1 + (following[2] - d1) * (t - t1) / (following[1] - t1)
    end
  end
  return 0.0
end
model:load_function{ name = "press", fn = press_depth }
model:fix{ node = tire.spindle, dofs = { "ux", "rz" } }
model:prescribe{ node = tire.spindle, dof = "uy", value = -1.0, load_function = "press" }

model:output{ file = p.output, fields_interval = p.fields_interval }
model:history{ name = "spindle_fx", node = tire.spindle, quantity = "spindle_force", component = "fx" }
model:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force", component = "fz" }
model:history{ name = "spin_rate", node = tire.spindle, quantity = "spin_rate" }
model:history{ name = "spindle_height", node = tire.spindle, dof = "uy" }

-- 0-1 s: inflation. The drum is defined after it: automatic contact penalties are scaled
-- from the structure's stiffness, and the uninflated tire has none to speak of.
model:solve{ to = 1.0, dt = 0.25 }
model:surface{ name = "drum", type = "drum", diameter = p.drum_diameter, cleat_height = p.cleat_height,
               cleat_length = p.cleat_length, cleat_angle = cleat_angle, edge_radius = p.cleat_edge_radius,
               speed = -omega, ramp_time = p.spin_up_time, start_time = dynamic_start }
model:contact{ surface = "drum", set = tire.contact_set, friction = p.friction, penalty = p.contact_penalty,
               tangential_factor = p.tangential_factor,
               tolerance = p.contact_tolerance, multiplier_tolerance = p.multiplier_tolerance, history = "drum",
               output_every = 20 }

-- 1-2 s: press. Five steps toward a first guess of the deflection, then secant steps on the
-- measured force-deflection curve until the spindle carries the load to 0.1 %.
local function spindle_fx() return model:value{ node = tire.spindle, quantity = "spindle_force", component = "fx" } end
local function spindle_fz() return model:value{ node = tire.spindle, quantity = "spindle_force", component = "fz" } end
local function press_to(depth, dt)
  press_path[#press_path + 1] = { model:time() + dt, depth }
  model:step{ dt = dt }
end
press_path[#press_path + 1] = { 1.0, 0.0 }
local guess = p.load / 170e3                    -- a passenger tire's vertical stiffness, about 170 N/mm
for k = 1, 5 do press_to(guess * k / 5, 0.1) end
local previous_depth, previous_load = 0.0, 0.0
for _ = 1, 8 do
  local depth, load = press_depth(model:time()), spindle_fz()
  if math.abs(load - p.load) < 1e-3 * p.load then break end
  local stiffness = (load - previous_load) / (depth - previous_depth)
  previous_depth, previous_load = depth, load
  press_to(depth + (p.load - load) / stiffness, 0.05)
end
if math.abs(spindle_fz() - p.load) > 1e-3 * p.load then
  error(string.format("pressing did not reach the load %g N (spindle force %g N)", p.load, spindle_fz()))
end
model:solve{ to = dynamic_start, dt = 0.1 }
local loaded_deflection = press_depth(model:time())
local spindle_fz_at_start = spindle_fz()
print(string.format("pressed: deflection %.2f mm for %.1f N, contact patch %.1f mm", loaded_deflection * 1e3,
                    spindle_fz(), model:contact_value{ name = "contact_drum", quantity = "patch_length" } * 1e3))

-- 2-8 s: the drum spins up; the spindle turns freely on the dead axle.
model:release{ node = tire.spindle, dofs = { "rz" } }
model:newton{ tolerance = p.newton_tolerance }
-- A step cut to a thousandth of dt means the solution is falling apart: stop with a message.
model:step_control{ min_dt = p.dt_cleat / 1024, max_cuts = 10 }
if p.integrator == "hht" then
  model:integrator{ type = "hht", alpha = p.alpha }
elseif p.integrator == "newmark" then
  model:integrator{ type = "newmark", gamma = p.newmark_gamma, beta = (p.newmark_gamma + 0.5) ^ 2 / 4 }
else
  error("parameter integrator must be hht or newmark, not '" .. p.integrator .. "'")
end

local record = { time = {}, fx = {}, fz = {}, spin = {} }
local totals = { steps = 0, newton = 0, cuts = 0 }
local wall_start = os.clock()  -- CPU time of this process
while model:time() < p.end_time - 1e-9 do
  local t = model:time()
  local dt = math.min(time_step(t), p.end_time - t)
  local step = model:step{ dt = dt }
  totals.steps, totals.newton, totals.cuts = totals.steps + step.steps, totals.newton + step.newton_iterations,
                                             totals.cuts + step.cuts
  t = model:time()
  record.time[#record.time + 1] = t
  record.fx[#record.fx + 1] = spindle_fx()
  record.fz[#record.fz + 1] = spindle_fz()
  record.spin[#record.spin + 1] = model:value{ node = tire.spindle, quantity = "spin_rate" }
end
local wall = os.clock() - wall_start
model:result{ name = "dynamic_steps", value = totals.steps }
model:result{ name = "dynamic_newton_iterations", value = totals.newton }
model:result{ name = "dynamic_cpu_time", value = wall, unit = "s" }
print(string.format("dynamic run: %d steps, %d Newton iterations (%.2f per step), %d cuts, %.2f s CPU, "
                    .. "%.1f us per iteration", totals.steps, totals.newton, totals.newton / totals.steps, totals.cuts,
                    wall, 1e6 * wall / totals.newton))

-- Summary of the last passage at full speed with its ringing recorded.
local function window_values(series, from, to)
  local low, high = math.huge, -math.huge
  for i, t in ipairs(record.time) do
    if t >= from and t <= to then low, high = math.min(low, series[i]), math.max(high, series[i]) end
  end
  return low, high
end
local full_speed = dynamic_start + p.spin_up_time
local last
for _, passage in ipairs(passages) do
  if passage.on >= full_speed and passage.off + p.ring_time <= p.end_time then last = passage end
end
local cleat_ringing = require("cleat_ringing")
local summary = {}
if last then
  local fx_low, fx_high = window_values(record.fx, last.on - 0.01, last.off + p.ring_time)
  local fz_low, fz_high = window_values(record.fz, last.on - 0.01, last.off + p.ring_time)
  summary.fx_peak_to_peak, summary.fz_peak_to_peak = fx_high - fx_low, fz_high - fz_low
  print(string.format("cleat passage at %.3f-%.3f s (%.1f km/h), every %.3f s at full speed", last.on, last.off,
                      p.speed_kmh, math.pi * p.drum_diameter / speed))
  print(string.format("  peak to peak: Fx %.0f N, Fz %.0f N", summary.fx_peak_to_peak, summary.fz_peak_to_peak))
  summary.ringing = cleat_ringing.read{ time = record.time, fx = record.fx, fz = record.fz, on = last.on,
                                        off = last.off, speed = speed }
  -- The measured column only for the test's own conditions.
  summary.measured = cleat_ringing.measured(p)
  cleat_ringing.report(model, summary.ringing, summary.measured)
  model:result{ name = "cleat_on_s", value = last.on, unit = "s" }
  model:result{ name = "cleat_off_s", value = last.off, unit = "s" }
  model:result{ name = "fx_peak_to_peak", value = summary.fx_peak_to_peak, unit = "N" }
  model:result{ name = "fz_peak_to_peak", value = summary.fz_peak_to_peak, unit = "N" }
  -- The period of the impacts at full speed: times of the Fz maxima of successive passages.
  local peaks = {}
  for _, passage in ipairs(passages) do
    if passage.on >= full_speed and passage.off + 0.01 <= p.end_time then
      local peak_time, peak = nil, -math.huge
      for i, t in ipairs(record.time) do
        if t >= passage.on - 0.01 and t <= passage.off + 0.01 and record.fz[i] > peak then peak_time, peak = t, record.fz[i] end
      end
      peaks[#peaks + 1] = peak_time
    end
  end
  if #peaks >= 2 then
    summary.impact_period = (peaks[#peaks] - peaks[1]) / (#peaks - 1)
    print(string.format("  Fz peaks every %.4f s over %d passages (pi D / v = %.4f s)", summary.impact_period, #peaks,
                        math.pi * p.drum_diameter / speed))
    model:result{ name = "impact_period", value = summary.impact_period, unit = "s" }
  end
end

-- Steady rolling just before the last passage: effective rolling radius = drum surface
-- speed / spin rate, averaged over 20 ms. The contact nodes stick to the drum through the
-- patch, so over one turn of the tire the drum advances by the length of the ring they
-- form: the rolling radius is its circumference over 2 pi, however deflected the tire is.
local rolling_radius, belt_radius
if last then
  local sum, count = 0, 0
  for i, t in ipairs(record.time) do
    if t > last.on - 0.03 and t <= last.on - 0.01 then sum, count = sum + speed / record.spin[i], count + 1 end
  end
  rolling_radius = sum / count
end
-- The polygon through the nodes that touch the drum (the tread nodes, or the tread
-- layer's nodes), closed.
local function contact_circumference()
  local length, first, previous = 0, nil, nil
  for _, node in ipairs(tire.contact) do
    local x = model:value{ node = node, dof = "ux", quantity = "position" }
    local y = model:value{ node = node, dof = "uy", quantity = "position" }
    if previous then length = length + math.sqrt((x - previous[1]) ^ 2 + (y - previous[2]) ^ 2) end
    previous, first = { x, y }, first or { x, y }
  end
  return length + math.sqrt((first[1] - previous[1]) ^ 2 + (first[2] - previous[2]) ^ 2)
end
if rolling_radius then
  belt_radius = contact_circumference() / (2 * math.pi)  -- at the end of the run, the belt rings little by then
  print(string.format("rolling radius before the cleat %.2f mm; contact ring circumference / 2 pi %.2f mm; unloaded "
                      .. "radius %.2f mm, loaded %.2f mm", rolling_radius * 1e3, belt_radius * 1e3,
                      tire_parameters.outer_diameter / 2 * 1e3,
                      (tire_parameters.outer_diameter / 2 - loaded_deflection) * 1e3))
end

if p.check then
  tirefe.check{ name = "pressed to the load [N]", value = spindle_fz_at_start, expected = p.load, tolerance = 1e-3 * p.load }
  tirefe.check{ name = "a full-speed cleat passage was run", value = last and 1 or 0, expected = 1, tolerance = 0 }
  tirefe.check{ name = "rolling radius = contact ring circumference / 2 pi [m]", value = rolling_radius, expected = belt_radius,
                tolerance = 2e-3 * belt_radius }
  if p.tire == "tires.145SR12_tread_layer" and summary.measured then
    -- The calibrated tire against the measured ringing (docs/calibration.md): each window's
    -- reading within 5 % of the measured frequency, and its two estimators within 5 % of each
    -- other. Fx from the first hit is not one mode's ringing (the passage's own content and the
    -- restart of the ringing as the tire leaves the cleat, docs/drum_cleat.md): it is checked
    -- against the model's documented reading instead.
    local measured = summary.measured
    for _, window in ipairs(cleat_ringing.windows) do
      local reading = summary.ringing[window.name]
      if window.name ~= "fx_from_hit" then
        tirefe.check{ name = window.what .. " vs measured " .. measured[window.name] .. " Hz",
                      value = reading.frequency, expected = measured[window.name], relative = 0.05 }
        tirefe.check{ name = window.what .. ": matrix pencil vs spectrum", value = reading.pencil_frequency,
                      expected = reading.spectrum_frequency, relative = 0.05 }
      end
    end
    tirefe.check{ name = "Fx from the first hit, the model's documented reading [Hz]",
                  value = summary.ringing.fx_from_hit.frequency, expected = 31.5, relative = 0.05 }
  end
end

return { summary = summary, rolling_radius = rolling_radius, passages = passages, record = record }
