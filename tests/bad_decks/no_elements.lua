-- expect line 6: the model has no elements: there are no equations to solve
-- Nodes and supports but no element joining them: nothing for the solver to analyse.
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
model:load{ node = a, fx = 1 }
model:solve{ to = 1, dt = 0.5 }
