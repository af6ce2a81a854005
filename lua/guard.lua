-- Guards for a deck's parameters: an error naming the first one out of its range.
--
--   local guard = require("guard")
--   guard.positive(p, { "load", "dt" })
--   guard.non_negative(p, { "cleat_height" })
local guard = {}

-- Each named parameter of p must be > 0 (a NaN is not).
function guard.positive(p, names)
  for _, name in ipairs(names) do
    if not (p[name] > 0) then error(string.format("parameter %s = %g must be positive", name, p[name]), 0) end
  end
end

-- Each named parameter of p must be >= 0.
function guard.non_negative(p, names)
  for _, name in ipairs(names) do
    if not (p[name] >= 0) then error(string.format("parameter %s = %g must not be negative", name, p[name]), 0) end
  end
end

return guard
