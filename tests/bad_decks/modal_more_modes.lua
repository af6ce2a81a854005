-- expect line 9: modal analysis: 10 modes asked of a model with 3 free equations (at most that many modes)
-- More modes than free equations: it used to return the three there are, silently.
local model = tirefe.model{ title = "names" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:modal{ modes = 10 }
