-- The summary of a drum-cleat run (docs/drum_cleat.md): the last two passages at full speed
-- whose ringing was recorded (the rig's read_passages: their readings differ with where the
-- tread nodes meet the cleat), each read for its peak-to-peak spindle forces and ringing
-- frequencies (lua/cleat_ringing.lua), both together, the impacts' period, and the rolling
-- radius just before the last.
-- Printed, and written to the model's /results.
--
--   local summary = require("cleat_summary").report{ model = model, rig = rig, passages = passages,
--     record = record, ring_time = 0.15, end_time = 8.0, speed_kmh = 51.3, measured = ...,
--     tread = tire.tread, unloaded_radius = 0.2715, deflection = 0.0251, elements = 100 }
local series, cleat_ringing, rolling = require("series"), require("cleat_ringing"), require("rolling")
local cleat_summary = {}

-- One passage read: its peak-to-peak forces over the passage and its ringing.
local function read_passage(args, passage)
  local record = args.record
  local fx_low, fx_high = series.range(record.time, record.fx, passage.on - 0.01, passage.off + args.ring_time)
  local fz_low, fz_high = series.range(record.time, record.fz, passage.on - 0.01, passage.off + args.ring_time)
  return { passage = passage, fx_peak_to_peak = fx_high - fx_low, fz_peak_to_peak = fz_high - fz_low,
           ringing = cleat_ringing.read{ time = record.time, fx = record.fx, fz = record.fz, on = passage.on,
                                         off = passage.off, speed = args.rig.speed } }
end

-- Prints a passage's peaks and ringing table and records them in /results, each name
-- with 'prefix' before it.
local function report_passage(args, reading, prefix)
  local model = args.model
  print(string.format("  peak to peak: Fx %.0f N, Fz %.0f N", reading.fx_peak_to_peak, reading.fz_peak_to_peak))
  cleat_ringing.report(model, reading.ringing, args.measured, prefix)
  model:result{ name = prefix .. "cleat_on_s", value = reading.passage.on, unit = "s" }
  model:result{ name = prefix .. "cleat_off_s", value = reading.passage.off, unit = "s" }
  model:result{ name = prefix .. "fx_peak_to_peak", value = reading.fx_peak_to_peak, unit = "N" }
  model:result{ name = prefix .. "fz_peak_to_peak", value = reading.fz_peak_to_peak, unit = "N" }
end

-- The two passages together: their peak-to-peak forces' mean +- half their difference, and
-- the tire's turn from one cleat's arrival to the next in node spacings (from the spindle's
-- rotation, record.turn, and args.elements): how far apart its tread nodes met the two
-- cleats, which sets the difference (docs/drum_cleat.md, "Two passages"). Returns the turn.
local function report_both(args, before, last)
  local model = args.model
  local fx, fz = (before.fx_peak_to_peak + last.fx_peak_to_peak) / 2, (before.fz_peak_to_peak + last.fz_peak_to_peak) / 2
  local text = string.format("both passages: Fx peak to peak %.0f +- %.0f N, Fz %.0f +- %.0f N (mean +- half the "
                             .. "difference)", fx, math.abs(last.fx_peak_to_peak - fx), fz,
                             math.abs(last.fz_peak_to_peak - fz))
  model:result{ name = "mean_fx_peak_to_peak", value = fx, unit = "N" }
  model:result{ name = "mean_fz_peak_to_peak", value = fz, unit = "N" }
  local turn
  if args.record.turn and args.elements then
    local record, spacing = args.record, 2 * math.pi / args.elements
    turn = math.abs(series.at(record.time, record.turn, last.passage.on)
                    - series.at(record.time, record.turn, before.passage.on)) / spacing
    local offset = turn - math.floor(turn)
    text = text .. string.format("\n  the tire turned %.2f node spacings from the one cleat to the other: its tread "
                                 .. "nodes met them %.2f of a spacing apart", turn, math.min(offset, 1 - offset))
    model:result{ name = "node_spacings_between_passages", value = turn }
  end
  print(text)
  return turn
end

-- args.record: the run's time, fx, fz and spin series (and turn, the spindle's rotation
-- [rad], which with args.elements, the tire's wedges, gives the node spacings between the
-- passages); args.measured: cleat_ringing.measured of the run's conditions (or nil). Returns the summary: the last passage, fx_peak_to_peak,
-- fz_peak_to_peak [N] and ringing of it, 'before' (the same for the passage before it, or
-- nil), measured, impact_period [s], rolling_radius and belt_radius [m] (the tread nodes'
-- ring circumference / 2 pi), node_spacings_between (the tire's turn from the one passage
-- to the other, or nil); empty without a passage. /results holds the last passage's
-- under their names, the one before's with "before_" in front.
function cleat_summary.report(args)
  local model, rig, record = args.model, args.rig, args.record
  local read = rig:read_passages(args.passages, args.ring_time, args.end_time)
  if #read == 0 then return {} end
  local last = read[#read]
  local summary = read_passage(args, last)
  summary.measured = args.measured
  if #read == 2 then
    summary.before = read_passage(args, read[1])
    print(string.format("cleat passage at %.3f-%.3f s (%.1f km/h), the one before the last", read[1].on, read[1].off,
                        args.speed_kmh))
    report_passage(args, summary.before, "before_")
  end
  print(string.format("cleat passage at %.3f-%.3f s (%.1f km/h), every %.3f s at full speed", last.on, last.off,
                      args.speed_kmh, rig:turn_time()))
  report_passage(args, summary, "")
  local passed
  summary.impact_period, passed = rig:impact_period(args.passages, record.time, record.fz, args.end_time)
  if summary.impact_period then
    print(string.format("  Fz peaks every %.4f s over %d passages (pi D / v = %.4f s)", summary.impact_period, passed,
                        rig:turn_time()))
    model:result{ name = "impact_period", value = summary.impact_period, unit = "s" }
  end
  if summary.before then summary.node_spacings_between = report_both(args, summary.before, summary) end
  -- Steady rolling before the passage: drum surface speed / spin rate over 20 ms, beside the
  -- tread nodes' ring at the end of the run (the belt rings little by then).
  summary.rolling_radius = rolling.radius{ time = record.time, spin = record.spin, speed = rig.speed,
                                           from = last.on - 0.03, to = last.on - 0.01 }
  summary.belt_radius = rolling.tread_circumference(model, args.tread) / (2 * math.pi)
  print(string.format("rolling radius before the cleat %.2f mm; tread ring circumference / 2 pi %.2f mm; unloaded "
                      .. "radius %.2f mm, loaded %.2f mm", summary.rolling_radius * 1e3, summary.belt_radius * 1e3,
                      args.unloaded_radius * 1e3, (args.unloaded_radius - args.deflection) * 1e3))
  return summary
end

return cleat_summary
