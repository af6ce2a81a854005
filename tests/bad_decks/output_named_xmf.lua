-- expect line 9: a result file named 'run.xmf' would be its own XDMF index (<name>.xmf is written beside it); give it the extension .h5
-- The index beside a result file takes its name with .xmf: a result file so named would collide with it.
local model = tirefe.model{ title = "names" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:output{ file = "run.xmf" }
