-- Stepping a model through a run on a time-step schedule, recording channels after each step.
--
--   local stepping = require("stepping")
--   local record, totals = stepping.run(model, { to = 8.0, time_step = function(t) return 1e-3 end,
--                                                channels = { fz = function() return ... end } })
--   stepping.report(model, totals, "dynamic")
--   stepping.integrator(model, { type = "newmark", gamma = 0.6 })
local stepping = {}

-- Steps to args.to with dt = args.time_step(t) (the last step shortened to land on it).
-- Returns the record (time and one list per channel of args.channels, if any, read after
-- each step; the result file's history channels cost less: model:history_values) and the
-- totals: steps taken (cut steps count each piece), Newton iterations, cuts and CPU time [s].
function stepping.run(model, args)
  local channels = args.channels or {}
  local record = { time = {} }
  for name in pairs(channels) do record[name] = {} end
  local totals = { steps = 0, newton = 0, cuts = 0 }
  local cpu_start = os.clock()  -- CPU time of this process
  while model:time() < args.to - 1e-9 do
    local t = model:time()
    local step = model:step{ dt = math.min(args.time_step(t), args.to - t) }
    totals.steps, totals.newton, totals.cuts = totals.steps + step.steps, totals.newton + step.newton_iterations,
                                               totals.cuts + step.cuts
    record.time[#record.time + 1] = model:time()
    for name, read in pairs(channels) do record[name][#record[name] + 1] = read() end
  end
  totals.cpu_time = os.clock() - cpu_start
  return record, totals
end

-- The model:integrator arguments of each scheme from a deck's parameters: "newmark" with
-- args.gamma and beta = (gamma + 1/2)^2 / 4 (unconditionally stable, dissipative for
-- gamma > 1/2), "hht" with args.alpha, "wbz" and "generalized_alpha" with args.rho_inf.
local schemes = {
  newmark = function(args) return { type = "newmark", gamma = args.gamma, beta = (args.gamma + 0.5) ^ 2 / 4 } end,
  hht = function(args) return { type = "hht", alpha = args.alpha } end,
  wbz = function(args) return { type = "wbz", rho_inf = args.rho_inf } end,
  generalized_alpha = function(args) return { type = "generalized_alpha", rho_inf = args.rho_inf } end,
}

-- Sets the model's time integrator by name (args.type); any other name is an error.
function stepping.integrator(model, args)
  local arguments = schemes[args.type]
  if not arguments then
    local names = {}
    for name in pairs(schemes) do names[#names + 1] = name end
    table.sort(names)
    error("parameter integrator must be one of " .. table.concat(names, ", ") .. ", not '" .. tostring(args.type)
          .. "'")
  end
  model:integrator(arguments(args))
end

-- Writes the totals as results NAME_steps, NAME_newton_iterations, NAME_cpu_time and prints them.
function stepping.report(model, totals, name)
  model:result{ name = name .. "_steps", value = totals.steps }
  model:result{ name = name .. "_newton_iterations", value = totals.newton }
  model:result{ name = name .. "_cpu_time", value = totals.cpu_time, unit = "s" }
  print(string.format("%s run: %d steps, %d Newton iterations (%.2f per step), %d cuts, %.2f s CPU, "
                      .. "%.1f us per iteration", name, totals.steps, totals.newton, totals.newton / totals.steps,
                      totals.cuts, totals.cpu_time, 1e6 * totals.cpu_time / totals.newton))
end

return stepping
