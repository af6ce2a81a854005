-- Readings of a recorded time series (parallel lists of times and values): extremes and
-- peaks in a time window, the mean of a function of the values over a window.
--
--   local series = require("series")
--   local low, high = series.range(record.time, record.fz, 2.4, 2.6)
--   local peak_time, peak = series.peak(record.time, record.fz, 2.4, 2.6)
--   local strike = series.rise(record.time, record.fz, 2.4, 2.6, 3700, 1850)
--   local turn = series.at(record.time, record.turn, 7.537)
--   local t, fz_200 = series.low_pass(record.time, record.fz, 200, 2.4, 2.6, 2.5e-4)
local series = {}

-- The lowest and highest value at times from <= t <= to (math.huge, -math.huge if none).
function series.range(time, values, from, to)
  local low, high = math.huge, -math.huge
  for i, t in ipairs(time) do
    if t >= from and t <= to then low, high = math.min(low, values[i]), math.max(high, values[i]) end
  end
  return low, high
end

-- The time and value of the largest value at times from <= t <= to (the first of equal ones;
-- nil, -math.huge if none).
function series.peak(time, values, from, to)
  local peak_time, peak = nil, -math.huge
  for i, t in ipairs(time) do
    if t >= from and t <= to and values[i] > peak then peak_time, peak = t, values[i] end
  end
  return peak_time, peak
end

-- The first time from <= t <= to at which the values rise through 'level' after having
-- been below 'below' (<= level) in the window: a load's return after an unloading, say.
-- Linear between the samples either side; nil if the values never do.
function series.rise(time, values, from, to, level, below)
  if below > level then error("series.rise: 'below' (" .. below .. ") is above 'level' (" .. level .. ")", 2) end
  local armed = false
  for i, t in ipairs(time) do
    if t > to then break end
    if t >= from then
      if armed and values[i] >= level then  -- the sample before was below 'level'
        local w = (level - values[i - 1]) / (values[i] - values[i - 1])
        return time[i - 1] + w * (t - time[i - 1])
      end
      if values[i] < below then armed = true end
    end
  end
  return nil
end

-- The mean of fn(value, t) over the samples at times from < t <= to (nil if none).
function series.mean(time, values, from, to, fn)
  local sum, count = 0, 0
  for i, t in ipairs(time) do
    if t > from and t <= to then sum, count = sum + fn(values[i], t), count + 1 end
  end
  if count == 0 then return nil end
  return sum / count
end

-- The value at time t, linear between the samples either side (nil outside the series).
function series.at(time, values, t)
  for i = 2, #time do
    if time[i] >= t and time[i - 1] <= t then
      local w = (t - time[i - 1]) / (time[i] - time[i - 1])
      return values[i - 1] + w * (values[i] - values[i - 1])
    end
  end
  return nil
end

-- The values low-passed at 'bandwidth' Hz without phase lag, as wheel-force transducer and
-- crash data are read (SAE J211-1, its channel frequency classes): the series resampled
-- every 'step' s over from <= t <= to (linear between samples), then a two-pole
-- Butterworth filter run forward and backward, which halves the gain at its corner twice:
-- its corner sits at bandwidth / 0.8023 so that the pair passes 'bandwidth' at -3 dB
-- (|H|^2 = 1 / (1 + (f / f_c)^4) = 1/2). Each pass starts settled on the value at its end.
-- Returns the new times and values.
function series.low_pass(time, values, bandwidth, from, to, step)
  if not (bandwidth > 0 and step > 0 and to > from) then
    error("series.low_pass: needs bandwidth > 0, step > 0 and to > from", 2)
  end
  if bandwidth * step >= 0.25 then
    error("series.low_pass: a " .. bandwidth .. " Hz bandwidth needs samples closer than " .. 0.25 / bandwidth .. " s", 2)
  end
  local times, x = {}, {}
  for k = 0, math.floor((to - from) / step + 1e-9) do
    local t = from + k * step
    local v = series.at(time, values, t)
    if v == nil then error("series.low_pass: the series does not cover t = " .. t .. " s", 2) end
    times[#times + 1], x[#x + 1] = t, v
  end
  local wa = math.tan(math.pi * (bandwidth / 0.8023) * step)  -- the corner, prewarped
  local d = 1 + math.sqrt(2) * wa + wa * wa
  local a0 = wa * wa / d
  local b1, b2 = -2 * (wa * wa - 1) / d, (-1 + math.sqrt(2) * wa - wa * wa) / d
  local function pass(input, first, last, increment)
    local out = {}
    local x1, x2, y1, y2 = input[first], input[first], input[first], input[first]
    for i = first, last, increment do
      local y = a0 * (input[i] + 2 * x1 + x2) + b1 * y1 + b2 * y2
      out[i], x2, x1, y2, y1 = y, x1, input[i], y1, y
    end
    return out
  end
  local forward = pass(x, 1, #x, 1)
  return times, pass(forward, #x, 1, -1)
end

-- The mean spacing of the given times (nil for fewer than two).
function series.mean_spacing(times)
  if #times < 2 then return nil end
  return (times[#times] - times[1]) / (#times - 1)
end

return series
