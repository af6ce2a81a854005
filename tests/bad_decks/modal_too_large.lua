-- expect line 10: modal analysis: the model has 2004 free equations, more than the 2000 a dense modal analysis solves in seconds
-- A dense modal analysis's time grows with the cube of the equations: 668 free nodes are
-- refused before it takes a quarter of a minute (10 000 equations took over 15 minutes).
local model = tirefe.model{ title = "long chain" }
local chain = {}
for i = 0, 668 do chain[#chain + 1] = model:node{ x = i / 100, y = 0 } end
model:section{ name = "s", EA = 1e6, GA = 1e6, EI = 10, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = chain }
model:fix{ node = chain[1] }
model:modal{ modes = 3 }
