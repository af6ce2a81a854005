-- expect line 3: speed_kmh = { default, "meaning", unit = "..." }: the unit must be a string, not a number
-- The unit is text.
local p = tirefe.parameters{
  speed_kmh = { 51.3, "final drum surface speed", unit = 3.6 },
}
