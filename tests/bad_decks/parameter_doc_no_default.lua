-- expect line 3: speed_kmh = { default, "meaning", unit = "..." }: the default comes first
-- A documented parameter without its default.
local p = tirefe.parameters{
  speed_kmh = { unit = "km/h" },
}
