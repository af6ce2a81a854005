-- A small calibrated tire on a spinning drum with a cleat, whose result file and
-- XDMF index tests/test_xdmf_readers.py reads back (with meshio among others). Inflated on
-- a held hub (0-1 s), pressed onto the drum (1-1.5 s), then the drum spins up and the
-- tire, its spin free, rolls; the cleat is still on its way round when the run ends.
--
--   tirefe tests/xdmf_deck.lua [elements=40] [end_time=1.8] [fields_interval=0.01] ...
local p = tirefe.parameters{ elements = 40, end_time = 1.8, dt = 2e-3, depth = 0.015, speed = 5.0,
                              fields_interval = 0.01, output = "xdmf.h5", views = true }

local model = tirefe.model{ title = "calibrated tire on a drum (XDMF readers)" }
local drum_radius = 0.85
local tire_parameters = {}
for key, value in pairs(require("tires.145SR12_tread_layer")) do tire_parameters[key] = value end
tire_parameters.elements = p.elements
tire_parameters.pressure_load_function = "inflation"
tire_parameters.y = drum_radius + tire_parameters.outer_diameter / 2
model:load_function{ name = "inflation", points = { { 0, 0 }, { 1, 1 }, { 1e9, 1 } } }
local tire = model:tire(tire_parameters)
model:output{ file = p.output, fields_interval = p.fields_interval, views = p.views }

model:load_function{ name = "press", points = { { 1, 0 }, { 1.5, 1 }, { 1e9, 1 } } }
model:fix{ node = tire.spindle, dofs = { "ux", "rz" } }
model:prescribe{ node = tire.spindle, dof = "uy", value = -p.depth, load_function = "press" }
model:solve{ to = 1.0, dt = 0.25 }

-- The drum turns clockwise: the cleat, 1.2 rad before the top, comes toward the tire.
model:surface{ name = "drum", type = "drum", diameter = 2 * drum_radius, cleat_height = 0.01, cleat_length = 0.2,
               cleat_angle = math.pi / 2 + 1.2, edge_radius = 0.003, speed = -p.speed / drum_radius,
               ramp_time = 0.2, start_time = 1.5 }
model:tire_contact{ surface = "drum", friction = 0.5, history = "drum" }
model:solve{ to = 1.5, dt = 0.05 }

model:release{ node = tire.spindle, dofs = { "rz" } }
model:integrator{ type = "hht", alpha = -0.1 }
model:solve{ to = p.end_time, dt = p.dt }
