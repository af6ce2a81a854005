-- expect line 3: key 'type' must be one of static, newmark, hht (got 'newmak')
local model = tirefe.model{}
model:integrator{ type = "newmak" }
