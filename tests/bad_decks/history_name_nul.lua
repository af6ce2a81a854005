-- expect line 9: key 'name' holds a NUL character (\0 at byte 4); give text without one
-- A NUL would cut the name short in the result file: the channel would be 'tip'.
local model = tirefe.model{ title = "names" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:history{ name = "tip\0uy", node = b, dof = "uy" }
