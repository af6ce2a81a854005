-- A spring pulled along its axis by a ramped force (model:axial_spring, docs/extending.md).
local model = tirefe.model{ title = "an axial spring pulled" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
local k, f = 2e4, 100
model:axial_spring{ nodes = { a, b }, stiffness = k }
model:fix{ node = a }
model:fix{ node = b, dofs = { "uy", "rz" } }
model:load{ node = b, fx = f }
model:history{ name = "spring_force", block = "springs", response = "axial_force" }
model:solve{ to = 1, dt = 0.5 }
tirefe.check{ name = "stretch f / k", value = model:value{ node = b, dof = "ux" }, expected = f / k, relative = 1e-12 }
tirefe.check{ name = "reaction at a", value = model:value{ node = a, dof = "ux", quantity = "reaction" },
              expected = -f, relative = 1e-12 }
local force = model:history_values{ name = "spring_force" }
tirefe.check{ name = "axial force, asked by name", value = force[#force], expected = f, relative = 1e-12 }
