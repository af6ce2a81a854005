-- expect line 8: node 3 has u_y held and u_x free; hold both or neither
local model = tirefe.model{}
local a, b, c = model:node{ x = 0, y = 0 }, model:node{ x = 1, y = 0 }, model:node{ x = 2, y = 0 }
model:section{ name = "bar", EA = 1e5, GA = 1e5, EI = 10, rhoA = 1, rhoI = 1e-4 }
model:beam{ section = "bar", nodes = { a, b, c } }
model:fix{ node = a }
model:fix{ node = c, dofs = { "uy" } }
model:modal{ modes = 2, damped = true, spin_rate = 10 }
