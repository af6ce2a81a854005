-- expect line 8: model 'growing' is busy in model:solve
-- A load function adding a node while the model solves would outgrow the state vectors.
local model = tirefe.model{ title = "growing" }
local a, b = model:node{ x = 0, y = 0 }, model:node{ x = 1, y = 0 }
model:section{ name = "bar", EA = 1e5, GA = 1e5, EI = 10, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "bar", nodes = { a, b } }
model:fix{ node = a }
model:load_function{ name = "grow", fn = function(t) model:node{ x = t, y = 1 } return t end }
model:load{ node = b, fx = 1, load_function = "grow" }
model:solve{ to = 1, dt = 0.5 }
