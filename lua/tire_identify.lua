-- A ring tire fitted to what a standard tire property file states (docs/tire.md, "Your tire
-- from a standard file"): the vertical stiffness at the nominal load, and MF-Swift's in-plane
-- modes of the belt against the held rim. Everything runs through model:tire, a press on a
-- flat road and model:modal, so the numbers are those a deck gets.
--
--   local identify = require("tire_identify")
--   local tp, stated = tirefe.read_tire{ file = "tires/HMMWV_Pac02Tire.tir" }
--   local result = identify.fit(tp, stated)     -- result.tp, result.residuals, result.measured
local press = require("press")

local identify = {}

local function copy(t)
  local out = {}
  for k, v in pairs(t) do out[k] = v end
  return out
end

-- Builds the tire on a held spindle and inflates it (quasi-static, 4 steps to t = 1).
local function inflated(tp, title)
  collectgarbage()                                   -- close the previous evaluation's file
  local model = tirefe.model{ title = title }
  local set = copy(tp)
  set.pressure_load_function = "inflate"
  model:load_function{ name = "inflate", points = { { 0, 0 }, { 1, 1 }, { 1e6, 1 } } }
  local tire = model:tire(set)
  model:fix{ node = tire.spindle }
  return model, tire
end

-- The vertical loads [N] of the inflated tire pressed on a flat, frictionless road to each
-- deflection [m] (from first touch, rising), in quasi-static steps of about 'step' [m].
function identify.vertical_loads(tp, deflections, step)
  local model, tire = inflated(tp, "tire on a flat road")
  local path = press.path(model, tire.spindle, "press")
  model:output{ file = "tire_identify_evaluation.h5" }
  model:solve{ to = 1.0, dt = 0.25 }
  local lowest = math.huge
  for i, node in ipairs(tire.tread) do
    local angle = 2 * math.pi * (i - 1) / #tire.tread
    lowest = math.min(lowest, 0.5 * tp.outer_diameter * math.sin(angle) + model:value{ node = node, dof = "uy" })
  end
  model:surface{ name = "road", type = "flat", point = { 0, lowest } }
  model:tire_contact{ surface = "road" }
  return path:load_curve(deflections, step or deflections[#deflections] / 10)
end

-- The belt's modes against the held rim of the inflated, unloaded tire: the translation
-- (fore-aft and vertical, a degenerate pair) and rotation (wind-up) frequencies [Hz], found
-- as the modes with the largest spindle force and moment; with damped = true the damped
-- frequencies and damping ratios instead.
function identify.hub_modes(tp, damped)
  local model, tire = inflated(tp, "belt modes on a held rim")
  model:output{ file = "tire_identify_evaluation.h5" }
  model:solve{ to = 1.0, dt = 0.25 }
  local f, r, zeta = model:modal{ modes = 10, reaction_node = tire.spindle, damped = damped or false }
  local translation, rotation, best_force, best_moment = nil, nil, -1, -1
  for i = 1, #f do
    local force, moment = math.sqrt(r[i][1] ^ 2 + r[i][2] ^ 2), math.abs(r[i][3])
    if force > best_force then translation, best_force = i, force end
    if moment > best_moment then rotation, best_moment = i, moment end
  end
  local modes = { translation = f[translation], rotation = f[rotation] }
  if damped then
    modes.translation_damping, modes.rotation_damping = zeta[translation], zeta[rotation]
  end
  return modes
end

-- The ring of the file 'stated.file' whose pressure acts on the width w, with the fitted
-- structural values of 'q' (k_gamma and the signed sidewall bending s k_sw) when given.
local function ring(stated, base, w, q)
  local tp = tirefe.read_tire{ file = stated.file, pressure = stated.pressure, tread_width = w }
  tp.elements = base.elements
  if q.k_gamma then tp.k_gamma = q.k_gamma end
  if q.bending then tp.k_sw, tp.k_sw_sign = math.abs(q.bending), q.bending < 0 and -1 or 1 end
  return tp
end

-- What the built tire does against what the file states: the vertical loads at half and all
-- of the nominal deflection, and the belt's modes on the held rim (damped: with ratios).
function identify.measure(tp, stated)
  local out = {}
  if stated.nominal_deflection then
    local d = stated.nominal_deflection
    local loads = identify.vertical_loads(tp, { 0.5 * d, d })
    out.half_load, out.nominal_load = loads[1], loads[2]
    out.vertical_stiffness = loads[2] / d
  end
  local modes = identify.hub_modes(tp, true)
  local undamped = identify.hub_modes(tp)
  out.translation, out.rotation = undamped.translation, undamped.rotation
  out.translation_damping, out.rotation_damping = modes.translation_damping, modes.rotation_damping
  return out
end

-- Fits the ring read from a standard file to what it states, through tirefe.fit:
--   the vertical load at the nominal deflection (= FNOMIN)  <- the width the pressure acts on
--   FREQ_WINDUP, the belt's rotation on the held rim         <- k_gamma
--   FREQ_LONG, the belt's translation on the held rim        <- the signed sidewall bending s k_sw
-- (each target only when the file states it; relative residuals). The other parameters keep
-- read_tire's values. Returns { tp = the fitted set, fit = tirefe.fit's result, residuals =
-- { vertical, translation, rotation } (relative), measured = identify.measure(tp, stated) }.
function identify.fit(tp, stated, options)
  options = options or {}
  local parameters, targets = {}, {}
  if stated.nominal_deflection then
    parameters[#parameters + 1] = { name = "w", initial = tp.tread_width, lower = 0.05 * tp.tread_width,
                                    upper = 2 * tp.tread_width, log = true }
    targets[#targets + 1] = "vertical"
  end
  if stated.windup_frequency then
    parameters[#parameters + 1] = { name = "k_gamma", initial = tp.k_gamma, lower = 1e-3 * tp.k_gamma,
                                    upper = 1e3 * tp.k_gamma, log = true }
    targets[#targets + 1] = "rotation"
  end
  if stated.longitudinal_frequency then
    local scale = 10 * tp.tread_EI
    parameters[#parameters + 1] = { name = "bending", initial = 0, lower = -1e3 * scale, upper = 1e3 * scale }
    targets[#targets + 1] = "translation"
  end
  assert(#parameters > 0, stated.file .. ": the file states neither a vertical stiffness nor in-plane modes")

  local function ratios(q)
    local set = ring(stated, tp, q.w or tp.tread_width, q)
    local out = {}
    local modes = (stated.windup_frequency or stated.longitudinal_frequency) and identify.hub_modes(set)
    for i, target in ipairs(targets) do
      if target == "vertical" then
        local d = stated.nominal_deflection
        out[i] = identify.vertical_loads(set, { d }, d / 8)[1] / stated.nominal_load
      elseif target == "rotation" then
        out[i] = modes.rotation / stated.windup_frequency
      else
        out[i] = modes.translation / stated.longitudinal_frequency
      end
    end
    return out
  end
  local data = {}
  for i = 1, #targets do data[i] = 1 end
  local fit = tirefe.fit{ parameters = parameters, data = data, model = ratios, tolerance = options.tolerance or 1e-4,
                          relative_step = 1e-3, log = options.log or false, max_evaluations = 60 }
  local fitted = ring(stated, tp, fit.values.w or tp.tread_width, fit.values)
  local residuals = {}
  for i, target in ipairs(targets) do residuals[target] = fit.prediction[i] - 1 end
  return { tp = fitted, fit = fit, residuals = residuals, measured = identify.measure(fitted, stated) }
end

return identify
