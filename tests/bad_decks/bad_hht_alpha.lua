-- expect line 3: HHT needs alpha in [-1/3, 0]
local model = tirefe.model{}
model:integrator{ type = "hht", alpha = -0.5 }
