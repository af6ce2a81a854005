-- expect line 5: no beam section named 'tred'
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:beam{ section = "tred", nodes = { a, b } }
