-- expect line 9: modal analysis: the model has 10200 free equations, more than the 10000 its dense matrices can hold
-- A dense modal analysis of 3400 free nodes would need three 0.8 GB matrices: refused first.
local model = tirefe.model{ title = "long chain" }
local chain = {}
for i = 0, 3400 do chain[#chain + 1] = model:node{ x = i / 100, y = 0 } end
model:section{ name = "s", EA = 1e6, GA = 1e6, EI = 10, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = chain }
model:fix{ node = chain[1] }
model:modal{ modes = 3 }
