-- Road files (docs/roads.md): the chuckhole of the vehicle experiment
-- (inputs/vehicle_pothole.lua: 760 mm long, 100 mm deep, vertical walls, under the left
-- wheels only) read from a road data file (inputs/roads/chuckhole.rdf, a poly_line in mm
-- with a left and a right track) and from a CSV file (inputs/roads/chuckhole.csv), placed
-- on the road by 'start' and 'offset', and checked against the built-in pothole profile
-- and flat road by projecting a grid of points onto each surface.
--
--   tirefe inputs/road_files.lua [start=3] [level=-0.28] [edge_radius=0.02]

local p = tirefe.parameters{
  start = { 3.0, "where the chuckhole starts along the road", unit = "m" },
  level = { -0.28, "road level (y)", unit = "m" },
  edge_radius = { 0.02, "rounding of the chuckhole's edges", unit = "m" },
}
local model = tirefe.model{ title = "road files" }

model:surface{ name = "built_in", type = "profile", pothole = { p.start, 0.76, 0.10 }, level = p.level,
               edge_radius = p.edge_radius }
model:surface{ name = "flat", type = "flat", point = { 0, p.level } }
model:surface{ name = "rdf_left", file = "roads/chuckhole.rdf", track = "left", start = p.start, offset = p.level,
               edge_radius = p.edge_radius }
model:surface{ name = "rdf_right", file = "roads/chuckhole.rdf", track = "right", start = p.start, offset = p.level }
model:surface{ name = "csv_left", type = "profile", file = "roads/chuckhole.csv", track = "left", start = p.start,
               offset = p.level, edge_radius = p.edge_radius }
model:surface{ name = "csv_right", type = "profile", file = "roads/chuckhole.csv", track = "right", start = p.start,
               offset = p.level }

-- The largest difference of gap and closest point between two surfaces over points from
-- 0.5 m before the hole to 0.5 m after it, 50 mm above the road to 150 mm below it.
local function largest_difference(a, b)
  local worst = 0
  for i = 0, 176 do
    for _, height in ipairs({ 0.05, 0.0, -0.05, -0.15 }) do
      local point = { p.start - 0.5 + 0.01 * i, p.level + height }
      local pa = model:surface_projection{ surface = a, point = point }
      local pb = model:surface_projection{ surface = b, point = point }
      worst = math.max(worst, math.abs(pa.gap - pb.gap), math.abs(pa.x - pb.x), math.abs(pa.y - pb.y))
    end
  end
  return worst
end

tirefe.check{ name = "left track of the .rdf = built-in pothole [m]",
              value = largest_difference("rdf_left", "built_in"), expected = 0, tolerance = 1e-12 }
tirefe.check{ name = "right track of the .rdf = flat road [m]", value = largest_difference("rdf_right", "flat"),
              expected = 0, tolerance = 1e-12 }
tirefe.check{ name = "left track of the .csv = built-in pothole [m]",
              value = largest_difference("csv_left", "built_in"), expected = 0, tolerance = 1e-12 }
tirefe.check{ name = "right track of the .csv = flat road [m]", value = largest_difference("csv_right", "flat"),
              expected = 0, tolerance = 1e-12 }
-- And the hole is there: 100 mm below the road in its middle.
local bottom = model:surface_projection{ surface = "rdf_left", point = { p.start + 0.38, p.level } }
tirefe.check{ name = "depth of the chuckhole [m]", value = bottom.gap, expected = 0.10, tolerance = 1e-12 }
