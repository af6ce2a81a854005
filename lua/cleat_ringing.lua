-- The ringing of the spindle forces after a cleat, read the way a tire engineer reads a
-- drum-cleat test (docs/drum_cleat.md): four windows, each read by tirefe.ringing (a Hann
-- spectrum peak and a matrix-pencil fit of the same samples; their mean, and half their
-- difference as the uncertainty).
--
--   local ringing = require("cleat_ringing")
--   local readings = ringing.read{ time = t, fx = fx, fz = fz, on = 7.537, off = 7.584, speed = 14.25 }
--   print(readings.fx_leaving.frequency, readings.fx_leaving.uncertainty)
--
-- on / off: when the cleat's leading / trailing edge passes the middle of the contact
-- patch [s]; speed: the drum's surface speed [m/s]. The patch reaches 'reach' (80 mm)
-- either side of its middle, so the tire first touches the cleat reach / speed before 'on'
-- and has left it reach / speed after 'off'.
local M = {}

M.reach = 0.08  -- [m]

-- name, force, start, duration [s], band [Hz]. The vertical windows look above 40 Hz
-- (below lie the fore-aft mode and the passage itself); the longitudinal ones from 15 Hz,
-- above the passage's own content (a 46 ms pulse at 51.3 km/h), up to 200 Hz.
M.windows = {
  { name = "fz_on_top", force = "fz", what = "Fz on top of the cleat", band = { 40, 200 },
    span = function(on, off, lag) return on + lag, off - lag end },
  { name = "fz_leaving", force = "fz", what = "Fz after leaving it, 100 ms", band = { 40, 200 },
    span = function(_, off, lag) return off + lag, off + lag + 0.10 end },
  { name = "fx_from_hit", force = "fx", what = "Fx from the first hit, 150 ms", band = { 15, 200 },
    span = function(on, _, lag) return on - lag, on - lag + 0.15 end },
  { name = "fx_leaving", force = "fx", what = "Fx after leaving it, 120 ms", band = { 15, 200 },
    span = function(_, off, lag) return off + lag, off + lag + 0.12 end },
}

-- The last time any window needs samples, after 'off'.
function M.duration_after(speed)
  return M.reach / speed + 0.12
end

function M.read(args)
  local lag = M.reach / args.speed
  local readings = {}
  for _, window in ipairs(M.windows) do
    local from, to = window.span(args.on, args.off, lag)
    local reading = tirefe.ringing{ time = args.time, values = args[window.force], from = from, to = to,
                                    min_frequency = window.band[1], max_frequency = window.band[2] }
    reading.from, reading.to, reading.what = from, to, window.what
    readings[window.name] = reading
  end
  return readings
end

-- The frequencies measured on the drum (the paper's section 3.1, docs/model.md section 7)
-- and the test they were measured in: they say nothing about other speeds, loads or cleats.
-- Fx from the first hit has none: the paper's one longitudinal frequency (35 Hz) is the
-- ringing after the tire leaves the cleat; the first hit's window holds the passage's own
-- content as well (docs/drum_cleat.md), this project's reading, reported and not scored.
M.measured_frequencies = { fz_on_top = 88, fz_leaving = 85, fx_leaving = 35 }
M.test_conditions = { speed_kmh = 51.3, load = 3800, pressure_kpa = 208, cleat_height = 0.025, cleat_length = 0.66,
                      drum_diameter = 1.7 }
M.test_note = "measured values are for 51.3 km/h, 3800 N, 208 kPa, 25 mm x 660 mm cleat on the 1.7 m drum"

-- The measured frequencies if every one of the run's 'conditions' (keys of M.test_conditions)
-- is the test's to 0.1 %, else nil.
function M.measured(conditions)
  for key, value in pairs(M.test_conditions) do
    local given = conditions[key]
    if type(given) ~= "number" or math.abs(given - value) > 1e-3 * value then return nil end
  end
  return M.measured_frequencies
end

-- The summary table's lines: with a "measured" column when 'measured' is given, else
-- without it and with a note saying which test the measurements are for.
function M.table_lines(readings, measured)
  local lines = { "  ringing                          spectrum   pencil  (damping)   reading"
                  .. (measured and "        measured" or "") }
  for _, window in ipairs(M.windows) do
    local r = readings[window.name]
    local line = string.format("  %-32s %6.1f Hz %6.1f Hz  (%5.3f)   %5.1f +- %4.1f Hz", r.what, r.spectrum_frequency,
                               r.pencil_frequency, r.damping_ratio, r.frequency, r.uncertainty)
    if measured then
      line = line .. (measured[window.name] and string.format("   %g Hz", measured[window.name]) or "   (none)")
    end
    lines[#lines + 1] = line
  end
  if not measured then lines[#lines + 1] = "  (" .. M.test_note .. ")" end
  return lines
end

-- Prints the readings as a table and records them in the model's /results:
-- <window>_Hz, <window>_uncertainty_Hz, <window>_spectrum_Hz, <window>_pencil_Hz,
-- <window>_damping_ratio, <window>_from_s, <window>_to_s, each with 'prefix' (default
-- none) in front. 'measured': M.measured(...).
function M.report(model, readings, measured, prefix)
  for _, line in ipairs(M.table_lines(readings, measured)) do print(line) end
  for _, window in ipairs(M.windows) do
    local r = readings[window.name]
    local results = { Hz = r.frequency, uncertainty_Hz = r.uncertainty, spectrum_Hz = r.spectrum_frequency,
                      pencil_Hz = r.pencil_frequency, damping_ratio = r.damping_ratio, from_s = r.from, to_s = r.to }
    for suffix, value in pairs(results) do
      local unit = suffix:match("_s$") and "s" or (suffix:match("Hz$") and "Hz" or nil)
      model:result{ name = (prefix or "") .. window.name .. "_" .. suffix, value = value, unit = unit }
    end
  end
end

-- Checks the calibrated tire's readings against the measured ringing (docs/calibration.md):
-- each measured window's reading within 5 % of the measurement, and its two estimators
-- within 5 % of each other. Fx from the first hit has no measurement (above): its spectrum
-- reading is checked against this model's own earlier reading, a regression check.
-- 'label' (optional) names the passage in the checks' names.
function M.check_calibrated(readings, measured, label)
  local of = label and (" (" .. label .. ")") or ""
  for _, window in ipairs(M.windows) do
    local reading = readings[window.name]
    if measured[window.name] then
      tirefe.check{ name = "measured: " .. window.what .. of .. " vs " .. measured[window.name] .. " Hz",
                    value = reading.frequency, expected = measured[window.name], relative = 0.05 }
      tirefe.check{ name = "estimators: " .. window.what .. of .. ", matrix pencil vs spectrum",
                    value = reading.pencil_frequency, expected = reading.spectrum_frequency, relative = 0.05 }
    end
  end
  tirefe.check{ name = "regression: Fx from the first hit" .. of .. ", spectrum vs this model's 31.0 Hz",
                value = readings.fx_from_hit.spectrum_frequency, expected = 31.0, relative = 0.03 }
end

return M
