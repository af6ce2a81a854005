-- The rolling radius of a tire on a moving surface, and the length of the ring its tread
-- nodes form: a tread that sticks to the surface through the patch carries it forward by
-- that length per turn of the tire, so the two give the same radius however deflected it is.
--
--   local rolling = require("rolling")
--   local r = rolling.radius{ time = record.time, spin = record.spin, speed = 14.25, from = 2.4, to = 2.42 }
--   local ring = rolling.tread_circumference(model, tire.tread) / (2 * math.pi)
local rolling = {}

-- Effective rolling radius [m]: the surface speed over the spin rate, averaged over the
-- samples at args.from < t <= args.to (time, spin: the recorded series; speed in m/s).
function rolling.radius(args)
  local sum, count = 0, 0
  for i, t in ipairs(args.time) do
    if t > args.from and t <= args.to then sum, count = sum + args.speed / args.spin[i], count + 1 end
  end
  return sum / count
end

-- The length [m] of the closed polygon through the given nodes' current positions (a
-- tire's tread nodes).
function rolling.tread_circumference(model, nodes)
  local length, first, previous = 0, nil, nil
  for _, node in ipairs(nodes) do
    local x = model:value{ node = node, dof = "ux", quantity = "position" }
    local y = model:value{ node = node, dof = "uy", quantity = "position" }
    if previous then length = length + math.sqrt((x - previous[1]) ^ 2 + (y - previous[2]) ^ 2) end
    previous, first = { x, y }, first or { x, y }
  end
  return length + math.sqrt((first[1] - previous[1]) ^ 2 + (first[2] - previous[2]) ^ 2)
end

return rolling
