-- expect line 15: the step budget ran out
-- keeps: step_budget.h5 1000
-- A cantilever with a tiny rotary inertia, started out of balance by a tip moment: its
-- steps converge only at 1.5e-8 s of a 1 ms dt and never grow back. The step budget stops the
-- run after 100 steps per nominal step (plus 100); its result file keeps every step.
local model = tirefe.model{ title = "out of balance" }
local chain = {}
for i = 0, 10 do chain[#chain + 1] = model:node{ x = i / 10, y = 0 } end
model:section{ name = "s", EA = 1e7, GA = 1e6, EI = 100, rhoA = 1, rhoI = 1e-9 }
model:beam{ section = "s", nodes = chain }
model:fix{ node = chain[1] }
model:load{ node = chain[#chain], mz = 500, fy = -2000, load_function = "constant" }
model:integrator{ type = "hht", alpha = -0.1 }
model:output{ file = "step_budget.h5" }
model:solve{ to = 0.01, dt = 1e-3 }
