-- The summary of a drum-cleat run (docs/drum_cleat.md): the last passage at full speed whose
-- ringing was recorded, read for its peak-to-peak spindle forces and ringing frequencies
-- (lua/cleat_ringing.lua), the impacts' period, and the rolling radius just before it.
-- Printed, and written to the model's /results.
--
--   local summary = require("cleat_summary").report{ model = model, rig = rig, passages = passages,
--     record = record, ring_time = 0.15, end_time = 8.0, speed_kmh = 51.3, measured = ...,
--     contact = tire.contact, unloaded_radius = 0.2715, deflection = 0.0251 }
local series, cleat_ringing, rolling = require("series"), require("cleat_ringing"), require("rolling")
local cleat_summary = {}

-- args.record: the run's time, fx, fz and spin series; args.measured: cleat_ringing.measured
-- of the run's conditions (or nil). Returns the summary: the passage, fx_peak_to_peak,
-- fz_peak_to_peak [N], ringing, measured, impact_period [s], rolling_radius and
-- belt_radius [m] (the contact nodes' ring circumference / 2 pi); empty without a passage.
function cleat_summary.report(args)
  local model, rig, record = args.model, args.rig, args.record
  local last = rig:last_full_speed_passage(args.passages, args.ring_time, args.end_time)
  if not last then return {} end
  local summary = { passage = last, measured = args.measured }
  local fx_low, fx_high = series.range(record.time, record.fx, last.on - 0.01, last.off + args.ring_time)
  local fz_low, fz_high = series.range(record.time, record.fz, last.on - 0.01, last.off + args.ring_time)
  summary.fx_peak_to_peak, summary.fz_peak_to_peak = fx_high - fx_low, fz_high - fz_low
  print(string.format("cleat passage at %.3f-%.3f s (%.1f km/h), every %.3f s at full speed", last.on, last.off,
                      args.speed_kmh, rig:turn_time()))
  print(string.format("  peak to peak: Fx %.0f N, Fz %.0f N", summary.fx_peak_to_peak, summary.fz_peak_to_peak))
  summary.ringing = cleat_ringing.read{ time = record.time, fx = record.fx, fz = record.fz, on = last.on,
                                        off = last.off, speed = rig.speed }
  cleat_ringing.report(model, summary.ringing, summary.measured)
  model:result{ name = "cleat_on_s", value = last.on, unit = "s" }
  model:result{ name = "cleat_off_s", value = last.off, unit = "s" }
  model:result{ name = "fx_peak_to_peak", value = summary.fx_peak_to_peak, unit = "N" }
  model:result{ name = "fz_peak_to_peak", value = summary.fz_peak_to_peak, unit = "N" }
  local passed
  summary.impact_period, passed = rig:impact_period(args.passages, record.time, record.fz, args.end_time)
  if summary.impact_period then
    print(string.format("  Fz peaks every %.4f s over %d passages (pi D / v = %.4f s)", summary.impact_period, passed,
                        rig:turn_time()))
    model:result{ name = "impact_period", value = summary.impact_period, unit = "s" }
  end
  -- Steady rolling before the passage: drum surface speed / spin rate over 20 ms, beside the
  -- contact nodes' ring at the end of the run (the belt rings little by then).
  summary.rolling_radius = rolling.radius{ time = record.time, spin = record.spin, speed = rig.speed,
                                           from = last.on - 0.03, to = last.on - 0.01 }
  summary.belt_radius = rolling.contact_circumference(model, args.contact) / (2 * math.pi)
  print(string.format("rolling radius before the cleat %.2f mm; contact ring circumference / 2 pi %.2f mm; unloaded "
                      .. "radius %.2f mm, loaded %.2f mm", summary.rolling_radius * 1e3, summary.belt_radius * 1e3,
                      args.unloaded_radius * 1e3, (args.unloaded_radius - args.deflection) * 1e3))
  return summary
end

return cleat_summary
