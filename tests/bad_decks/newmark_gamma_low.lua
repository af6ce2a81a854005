-- expect line 4: got beta = 0.25, gamma = 0.4
-- gamma below 1/2 makes every amplitude grow, at any step size.
local model = tirefe.model{}
model:integrator{ type = "newmark", gamma = 0.4 }
