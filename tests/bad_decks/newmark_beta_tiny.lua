-- expect line 4: Newmark needs 1/2 <= gamma <= 1 and gamma/2 <= beta <= 1
-- A vanishing beta is not an implicit scheme: the tangent factor 1/(beta h^2) overflows.
local model = tirefe.model{}
model:integrator{ type = "newmark", beta = 1e-300 }
