-- expect line 3: tirefe.parameters: speed_kmh = { default, "meaning", unit = "..." } takes no key 'units'
-- A documented parameter takes its default, a meaning and a unit, nothing else.
local p = tirefe.parameters{
  speed_kmh = { 51.3, "final drum surface speed", units = "km/h" },
}
