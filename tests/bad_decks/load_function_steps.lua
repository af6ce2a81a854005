-- expect line 8: model 'stepping' is busy in model:step
-- A load function stepping its own model would write steps inside a step (or recurse).
local model = tirefe.model{ title = "stepping" }
local a, b = model:node{ x = 0, y = 0 }, model:node{ x = 1, y = 0 }
model:section{ name = "bar", EA = 1e5, GA = 1e5, EI = 10, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "bar", nodes = { a, b } }
model:fix{ node = a }
model:load_function{ name = "again", fn = function(t) model:step() return t end }
model:load{ node = b, fx = 1, load_function = "again" }
model:step{ dt = 0.5 }
