-- expect line 3: key 'type' must be one of static, newmark, hht, wbz, generalized_alpha (got 'newmak')
local model = tirefe.model{}
model:integrator{ type = "newmak" }
