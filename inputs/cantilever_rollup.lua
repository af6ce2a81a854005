-- A cantilever rolled into a full circle by an end moment M = 2 pi EI / L.
-- Constant curvature M / EI = 2 pi / L bends the beam into a circle of radius L / (2 pi):
-- the tip turns by 2 pi and comes back to the root. With N straight elements the nodes
-- lie on a regular N-gon, so the middle node misses the top of the circle, (0, L/pi),
-- by about (L/pi) pi^2 / (6 N^2): the error falls as (1/N)^2. This deck checks itself.
--
--   tirefe inputs/cantilever_rollup.lua [elements=32]

local p = tirefe.parameters{
  elements = { 32, "beam elements (even)" },
  length = { 1.0, "cantilever length L", unit = "m" },
  EI = { 2.0, "bending stiffness", unit = "N m^2" },
  steps = { 8, "load steps" },
}
assert(p.elements % 2 == 0, "elements must be even (the check uses the middle node)")

local model = tirefe.model{ title = "Cantilever rolled up by an end moment" }
local chain = {}
for i = 0, p.elements do
  chain[#chain + 1] = model:node{ x = p.length * i / p.elements, y = 0.0 }
end
local root, middle, tip = chain[1], chain[p.elements / 2 + 1], chain[#chain]

local stiff = 1e7 * p.EI / p.length ^ 2
model:section{ name = "beam", EA = stiff, GA = stiff, EI = p.EI }
model:beam{ section = "beam", nodes = chain }
model:fix{ node = root }
model:load{ node = tip, mz = 2 * math.pi * p.EI / p.length }

model:output{ file = "cantilever_rollup.h5", fields_every = 1 }
model:history{ name = "tip_rotation", node = tip, dof = "rz" }
model:solve{ to = 1.0, dt = 1.0 / p.steps }

local L = p.length
tirefe.check{ name = "tip rotation = 2 pi", value = model:value{ node = tip, dof = "rz" },
              expected = 2 * math.pi, relative = 1e-9 }
tirefe.check{ name = "tip back at the root (x)", value = L + model:value{ node = tip, dof = "ux" },
              expected = 0.0, tolerance = 1e-6 * L }
tirefe.check{ name = "tip back at the root (y)", value = model:value{ node = tip, dof = "uy" },
              expected = 0.0, tolerance = 1e-6 * L }
-- Middle node at the top of the circle, missed by 2 (R_N - R) ~ (L/pi) pi^2 / (6 N^2).
local x = L / 2 + model:value{ node = middle, dof = "ux" }
local y = model:value{ node = middle, dof = "uy" }
local polygon_error = (L / math.pi) * math.pi ^ 2 / (6 * p.elements ^ 2)
tirefe.check{ name = "middle node at (0, L/pi)", value = math.sqrt(x ^ 2 + (y - L / math.pi) ^ 2),
              expected = polygon_error, relative = 0.05 }
