-- expect line 9: history channel name 'tip/x' must be a non-empty name without '/'
-- HDF5 reads a '/' as a group path: the name is refused at the history macro, not at the first step.
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:history{ name = "tip/x", node = b, dof = "ux" }
model:solve{ to = 1, dt = 0.5 }
