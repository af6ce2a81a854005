-- A wheel's strike on an obstacle, read the way wheel-force transducer data are read: its
-- spindle forces raw and low-passed at a stated bandwidth without phase lag, and the
-- tire's own account of it, its energy balance and its contact force from step to step
-- (docs/vehicle.md, "The strike").
--
--   local strike = require("strike")
--   local s = strike.read{ time = run.time, fx = corner.fx, fz = corner.fz, model = corner.model,
--                          from = 9.0, to = 9.15, static = 3715, bandwidth = 200, step = 2.5e-4 }
--   print(s.time, s.fz_peak, s.fz_peak_filtered, s.energy_error / s.surface_work)
local series = require("series")

local strike = {}

-- From every step at from <= t <= to of the wheel's spindle forces (time, fx, fz: ISO 8855
-- wheel axes) and of its tire's history (model: the tire's model, its contact's history
-- prefixed "patch"):
--   time                     where the load rises back through 'static' after dropping below
--                            half of it (nil if it never does; then only the peaks are read)
--   fz_peak, fx_low, fx_high the raw extremes, and *_filtered, the extremes low-passed at
--                            'bandwidth' Hz (series.low_pass, samples every 'step' s)
--   contact_jump             the largest step-to-step change of the contact's vertical force,
--                            over its largest value
--   surface_work             what the road did on the tire over the contact that strikes (from
--                            the step where the tire touches again to the step it leaves) [J]
--   energy_error, step_error the balance's error over it and its largest change in one step [J]
-- The energy and contact readings are nil where the tire's history is not in this process
-- (an MPI rank that does not own it).
function strike.read(args)
  local s = {}
  s.time = series.rise(args.time, args.fz, args.from, args.to, args.static, 0.5 * args.static)
  local _, fz_peak = series.peak(args.time, args.fz, args.from, args.to)
  s.fz_peak = fz_peak
  s.fx_low, s.fx_high = series.range(args.time, args.fx, args.from, args.to)
  local grid, fz = series.low_pass(args.time, args.fz, args.bandwidth, args.from, args.to, args.step)
  local _, fx = series.low_pass(args.time, args.fx, args.bandwidth, args.from, args.to, args.step)
  _, s.fz_peak_filtered = series.peak(grid, fz, args.from, args.to)
  s.fx_low_filtered, s.fx_high_filtered = series.range(grid, fx, args.from, args.to)

  local history = function(name) return args.model:history_values{ name = name } end
  local time, normal = history("time"), history("patch_fy")
  if #time == 0 then return s end
  local in_contact, surface, error = history("patch_nodes_in_contact"), history("surface_work"),
                                     history("energy_balance_error")
  local peak, jump, first, flying = 0, 0, nil, false
  for i = 2, #time do
    if time[i] >= args.from and time[i] <= args.to then
      peak = math.max(peak, math.abs(normal[i]))
      jump = math.max(jump, math.abs(normal[i] - normal[i - 1]))
      -- The strike: the contact that begins after the wheel has flown over the hole.
      if in_contact[i] == 0 and not first then flying = true end
      if in_contact[i] > 0 and flying and not first then first = i - 1 end
    end
  end
  s.contact_jump = peak > 0 and jump / peak or nil
  if first then
    local last = first + 1
    while last < #time and in_contact[last] > 0 do last = last + 1 end
    s.surface_work = surface[last] - surface[first]
    s.energy_error = error[last] - error[first]
    s.step_error = 0
    for i = first + 1, last do s.step_error = math.max(s.step_error, math.abs(error[i] - error[i - 1])) end
    s.contact_from, s.contact_to = time[first], time[last]
  end
  return s
end

return strike
