-- Automatic step cutting: the cantilever of the elastica deck loaded to P L^2/EI = 10 in ONE
-- step with at most 6 Newton iterations per try. The first try fails, the step is halved
-- until Newton converges, then grows back; the history's 'cuts' and 'step_size' channels
-- show it. The end state must still be the elastica's. This deck checks itself.

local model = tirefe.model{ title = "Step cutting on a one-step elastica" }
local chain = {}
for i = 0, 20 do chain[#chain + 1] = model:node{ x = i / 20, y = 0.0 } end
model:section{ name = "beam", EA = 1e5, GA = 1e5, EI = 1.0 }
model:beam{ section = "beam", nodes = chain }
model:fix{ node = chain[1] }
model:load{ node = chain[#chain], fy = -10.0 }

model:output{ file = "step_cut.h5" }
model:newton{ max_iterations = 6 }
local summary = model:solve{ to = 1.0, dt = 1.0 }
print(string.format("%d accepted steps after %d cuts", summary.steps, summary.cuts))

tirefe.check{ name = "the first try was cut", value = summary.cuts >= 1 and 1 or 0, expected = 1 }
tirefe.check{ name = "reached the end time", value = model:time(), expected = 1.0, tolerance = 1e-12 }
tirefe.check{ name = "tip deflection / L (elastica, 20 elements)", value = -model:value{ node = chain[#chain], dof = "uy" },
              expected = 0.81061, tolerance = 3e-3 }
