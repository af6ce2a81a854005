-- Tip-loaded cantilever, large deflection: the classic elastica check.
-- A straight, nearly inextensible cantilever of length L under a dead tip load P
-- perpendicular to its axis. For P L^2 / EI = 10 the tip moves down 0.81061 L and back
-- 0.55500 L (Mattiasson 1981, elliptic-integral solution). This deck checks itself.
--
--   tirefe inputs/cantilever_elastica.lua [elements=40] [load_parameter=10]

local p = tirefe.parameters{
  elements = { 40, "beam elements" },
  length = { 1.0, "cantilever length L", unit = "m" },
  EI = { 1.0, "bending stiffness", unit = "N m^2" },
  load_parameter = { 10.0, "tip load P L^2 / EI" },
  steps = { 10, "load steps" },
}

local model = tirefe.model{ title = "Tip-loaded cantilever (elastica)" }

local first, last
for i = 0, p.elements do
  local node = model:node{ x = p.length * i / p.elements, y = 0.0 }
  first = first or node
  last = node
end
model:node_set{ name = "root", nodes = { first } }
model:node_set{ name = "tip", nodes = { last } }

-- Axial and shear stiffness far above EI / L^2: the inextensible elastica.
local stiff = 1e7 * p.EI / p.length ^ 2
model:section{ name = "beam", EA = stiff, GA = stiff, EI = p.EI }
local chain = {}
for node = first, last do chain[#chain + 1] = node end
model:beam{ section = "beam", nodes = chain }

model:fix{ set = "root" }
local P = p.load_parameter * p.EI / p.length ^ 2
model:load{ set = "tip", fy = -P }          -- ramped: f(t) = t, full load at t = 1

model:output{ file = "cantilever_elastica.h5", fields_every = 1 }
model:history{ name = "tip_ux", set = "tip", dof = "ux" }
model:history{ name = "tip_uy", set = "tip", dof = "uy" }
model:history{ name = "tip_rotation", set = "tip", dof = "rz" }
model:history{ name = "root_force_y", set = "root", dof = "uy", quantity = "reaction" }

model:solve{ to = 1.0, dt = 1.0 / p.steps }

local deflection = -model:value{ set = "tip", dof = "uy" } / p.length
local shortening = -model:value{ set = "tip", dof = "ux" } / p.length
print(string.format("tip deflection %.5f L, shortening %.5f L", deflection, shortening))
if p.load_parameter == 10.0 then
  tirefe.check{ name = "tip deflection / L (elastica 0.81061)", value = deflection, expected = 0.81061, tolerance = 1e-3 }
  tirefe.check{ name = "tip shortening / L (elastica 0.55500)", value = shortening, expected = 0.55500, tolerance = 1e-3 }
end
tirefe.check{ name = "root reaction = P", value = model:value{ set = "root", dof = "uy", quantity = "reaction" },
              expected = P, relative = 1e-9 }
