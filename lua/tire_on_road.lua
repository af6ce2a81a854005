-- Shared by the decks that put a tire on a road: build it, inflate it on a held hub, and
-- find where a road must lie to touch it.
--
--   local tire_on_road = require("tire_on_road")
--   local tire, level = tire_on_road.inflated(model, require("tires.145SR12"))
local tire_on_road = {}

-- Builds the tire from a parameter set (the table is not changed), holds its spindle and
-- inflates it from 0 to 1 s in four steps (the pressure on the load function "inflate").
-- Returns the tire and the height of its lowest tread node: a road at that level touches it.
function tire_on_road.inflated(model, parameters)
  local copy = {}
  for key, value in pairs(parameters) do copy[key] = value end
  copy.pressure_load_function = "inflate"
  model:load_function{ name = "inflate", points = { { 0, 0 }, { 1, 1 } } }
  local tire = model:tire(copy)
  model:fix{ node = tire.spindle }
  model:solve{ to = 1.0, dt = 0.25 }
  local level = math.huge
  for _, node in ipairs(tire.tread) do
    level = math.min(level, model:value{ node = node, dof = "uy", quantity = "position" })
  end
  return tire, level
end

return tire_on_road
