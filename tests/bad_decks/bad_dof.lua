-- expect line 4: key 'dofs' entry 1 must be one of ux, uy, rz (got 'uz')
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
model:fix{ node = a, dofs = { "uz" } }
