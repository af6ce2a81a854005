-- A quarter car whose tire model is owned by MPI rank 1 of two (models 2 and 4; models
-- 1 and 3 are spacers), read after the vehicle advanced it: rank 0's copy is stale and
-- the read is refused (tests/test_mpi_vehicle.py). With again = 1 the owner goes on into
-- a second quarter car and waits there for rank 0's replies: rank 0 must end the job
-- instead of leaving it hanging.
local p = tirefe.parameters{ again = 0 }

local function quarter_car(title)
  tirefe.model{ title = "spacer" }
  local model = tirefe.model{ title = title }
  local tire, level = require("tire_on_road").inflated(model, require("tires.145SR12"))
  model:surface{ name = "road", type = "flat", point = {0, level} }
  model:tire_contact{ surface = "road", friction = 0.9 }
  model:load_function{ name = "press", points = {{1, 0}, {2, -0.015}} }
  model:prescribe{ node = tire.spindle, dof = "uy", value = 1, load_function = "press" }
  model:solve{ to = 2, dt = 0.25 }
  model:integrator{ type = "hht", alpha = -0.05 }
  tirefe.vehicle{ body = { mass = 300 }, duration = 0.01, dt = 2e-3, corners = {
    { model = model, spindle = tire.spindle, mass = 30, spring_rate = 2e4, preload = 2400, damping = 2000 } } }
  return model, tire
end

local model, tire = quarter_car("stale quarter car tire")
print(model:value{ node = tire.spindle, dof = "uy", quantity = "reaction" })
if p.again == 1 then quarter_car("second quarter car tire") end
