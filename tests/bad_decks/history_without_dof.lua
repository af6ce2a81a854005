-- expect line 4: quantity "reaction" needs dof = "ux", "uy" or "rz"
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
model:history{ name = "support", node = a, quantity = "reaction" }
