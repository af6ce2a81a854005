-- A small, fast deck for the sweep test (tests/test_sweep.py): a cantilever under a
-- suddenly applied tip load P = load_parameter * EI / L^2 vibrates about its static
-- deflection at its first bending frequency, f1 = 1.8751^2 / (2 pi) sqrt(EI / (rhoA L^4))
-- = 5.596 Hz for the values below. The deflection peaks at twice the static one.
--
--   tirefe tests/sweep_deck.lua [elements=4] [load_parameter=0.01] [max_deflection=1]
--
-- load_parameter <= 0 is refused (a deck error); a small max_deflection fails the
-- deck's self-check (exit status 3).

local p = tirefe.parameters{ elements = 4, load_parameter = 0.01, max_deflection = 1.0, steps = 200, duration = 2.0 }
if p.load_parameter <= 0 then error("load_parameter must be positive, got " .. p.load_parameter) end

local length, EI = 1.0, 100.0
local model = tirefe.model{ title = "Cantilever under a suddenly applied tip load" }
local chain = {}
for i = 0, p.elements do chain[#chain + 1] = model:node{ x = length * i / p.elements, y = 0.0 } end
model:node_set{ name = "tip", nodes = { chain[#chain] } }
model:section{ name = "beam", EA = 1e7, GA = 1e7, EI = EI, rhoA = 1.0, rhoI = 1e-6 }
model:beam{ section = "beam", nodes = chain }
model:fix{ node = chain[1] }
model:integrator{ type = "newmark" }
model:load{ set = "tip", fy = -p.load_parameter * EI / length ^ 2, load_function = "constant" }

model:output{ file = "sweep_cantilever.h5" }
model:history{ name = "tip_uy", set = "tip", dof = "uy" }
model:solve{ to = p.duration, dt = p.duration / p.steps }

tirefe.check{ name = "tip deflection / L within the limit", value = -model:value{ set = "tip", dof = "uy" } / length,
              expected = 0.0, tolerance = p.max_deflection }
