-- A tire built by a deck and handed to a host program through the C API
-- (tirefe_open_deck, docs/coupling.md): the 145 SR-12 inflated on a held hub, pressed
-- onto a flat road, made dynamic, then named for the host. Before handing it over, the
-- deck solves a trial step of its own with model:spindle_force and prints the force, so
-- that tests/capi_deck_host.c can solve the same step through the C API and compare.
--
--   (opened by a host)  tirefe_open_deck("host_tire_deck.lua", {"depth=0.012"}, 1, ...)
local p = tirefe.parameters{ depth = 0.01, friction = 0.8 }

local model = tirefe.model{ title = "a tire for a host" }
local tp = require("tires.145SR12")
local tire, level = require("tire_on_road").inflated(model, tp)
model:surface{ name = "road", type = "flat", point = { 0, level } }
model:tire_contact{ surface = "road", friction = p.friction }
model:load_function{ name = "press", points = { { 1, 0 }, { 2, 1 } } }
model:prescribe{ node = tire.spindle, dof = "uy", value = -p.depth, load_function = "press" }
model:solve{ to = 2.0, dt = 0.25 }
model:integrator{ type = "newmark" }

local s = model:spindle_force{ node = tire.spindle, x = 0, y = -p.depth - 1e-4, dt = 1e-3 }  -- a trial only
print(string.format("deck fy %.17g", s.fy))
host_tire = { model = model, spindle = tire.spindle }
