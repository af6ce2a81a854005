-- expect line 10: the model has no equations to solve: every DOF is fixed or prescribed
-- A beam held at both its nodes: no DOF left to solve for.
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:fix{ node = b }
model:step()
