-- Inflation of the 145 SR-12 tire on a fixed hub, quasi-static, 0 -> 0.208 MPa.
-- The inflated tire must stay round (every tread node at one radius) with no force on
-- the spindle; the deck prints the radial growth. This deck checks itself.
--
--   tirefe inputs/tire_inflation.lua [elements=100] [pressure_kpa=208]

local p = tirefe.parameters{
  elements = { 100, "wedges around the tire" },
  pressure_kpa = { 208.0, "inflation pressure", unit = "kPa" },
  steps = { 4, "load steps" },
}

local model = tirefe.model{ title = "145 SR-12 inflation on a fixed hub" }
local parameters = require("tires.145SR12")
parameters.elements = p.elements
parameters.pressure = p.pressure_kpa * 1e3
local tire = model:tire(parameters)
model:fix{ node = tire.spindle }

model:output{ file = "tire_inflation.h5", fields_every = 1 }
model:history{ name = "spindle_fx", node = tire.spindle, quantity = "spindle_force", component = "fx" }
model:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force", component = "fz" }
local summary = model:solve{ to = 1.0, dt = 1.0 / p.steps }
print(string.format("inflated in %d steps, %d Newton iterations", summary.steps, summary.newton_iterations))

-- Radii of the tread nodes after inflation.
local smallest, largest = math.huge, 0
local radius0 = parameters.outer_diameter / 2
for i, node in ipairs(tire.tread) do
  local angle = 2 * math.pi * (i - 1) / #tire.tread
  local x = radius0 * math.cos(angle) + model:value{ node = node, dof = "ux" }
  local y = radius0 * math.sin(angle) + model:value{ node = node, dof = "uy" }
  local r = math.sqrt(x * x + y * y)
  smallest, largest = math.min(smallest, r), math.max(largest, r)
end
print(string.format("radial growth %.3f mm (radius %.2f -> %.2f mm)", (largest - radius0) * 1e3,
                    radius0 * 1e3, largest * 1e3))
tirefe.check{ name = "round: radius spread / radius", value = (largest - smallest) / radius0, expected = 0,
              tolerance = 1e-9 }
local function spindle(component)
  return model:value{ node = tire.spindle, quantity = "spindle_force", component = component }
end
tirefe.check{ name = "spindle Fx [N]", value = spindle("fx"), expected = 0, tolerance = 1e-6 }
tirefe.check{ name = "spindle Fz [N]", value = spindle("fz"), expected = 0, tolerance = 1e-6 }
