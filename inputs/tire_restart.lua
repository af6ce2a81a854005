-- A rolling tire that can be stopped and continued (docs/restart.md): the 145 SR-12 (the
-- paper's model) is inflated on a held hub, pressed onto a flat road, and rolled by the
-- road accelerating to 'speed'. It writes a checkpoint every 'every_steps' dynamic steps
-- and one once the tire rolls at full speed; `tirefe inputs/tire_restart.lua --restart
-- results/rolling.ckpt.h5` continues from it and writes the same result file, bit for bit.
--
-- A restart skips the solves before its checkpoint, so nothing before it may depend on
-- computed results: the road's level and the press depth are given, not measured.
--
--   tirefe inputs/tire_restart.lua [speed=8] [end_time=2.6] [every_steps=100]

local p = tirefe.parameters{
  elements = { 100, "wedges around the tire" },
  pressure_kpa = { 208, "inflation pressure", unit = "kPa" },
  press = { 0.025, "spindle travel toward the road after inflation", unit = "m" },
  gap = { 0.004, "road below the unloaded tire before inflation", unit = "m" },
  speed = { 8.0, "road speed after the ramp", unit = "m/s" },
  ramp_time = { 0.2, "time the road takes to reach its speed, from t = 2 s", unit = "s" },
  dt = { 1e-3, "dynamic time step", unit = "s" },
  rolling_time = { 2.3, "time of the named checkpoint, the tire rolling at full speed", unit = "s" },
  end_time = { 2.6, "end of the run", unit = "s" },
  every_steps = { 100, "dynamic steps between automatic checkpoints" },
}

local model = tirefe.model{ title = "145 SR-12 rolling on a flat road (restartable)" }
model:output{ file = "tire_restart.h5", fields_interval = 0.01 }
local parameters = require("tires.145SR12")
parameters.elements = p.elements
parameters.pressure = p.pressure_kpa * 1e3
parameters.pressure_load_function = "inflate"
model:load_function{ name = "inflate", points = { { 0, 0 }, { 1, 1 }, { 1e9, 1 } } }
local tire = model:tire(parameters)

-- 0-1 s inflation on the held hub, 1-2 s pressed down onto the road, then rolling.
model:fix{ node = tire.spindle, dofs = { "ux", "rz" } }
local path = require("press").path(model, tire.spindle, "press")  -- holds the spindle's height (lua/press.lua)
model:surface{ name = "road", type = "flat", point = { 0, -parameters.outer_diameter / 2 - p.gap },
               speed = -p.speed, ramp_time = p.ramp_time, start_time = 2.0 }
model:tire_contact{ surface = "road", friction = 0.8, history = "patch", output_every = 10 }

model:history{ name = "spindle_fx", node = tire.spindle, quantity = "spindle_force", component = "fx" }
model:history{ name = "spindle_fz", node = tire.spindle, quantity = "spindle_force", component = "fz" }
model:history{ name = "spin_rate", node = tire.spindle, quantity = "spin_rate" }

model:solve{ to = 1.0, dt = 0.25 }
path:move_to(p.press, 10, 0.1)

model:release{ node = tire.spindle, dofs = { "rz" } }
model:integrator{ type = "hht", alpha = -0.1 }
model:checkpoint{ file = "auto.ckpt.h5", every_steps = p.every_steps }
model:solve{ to = p.rolling_time, dt = p.dt }
model:checkpoint{ file = "rolling.ckpt.h5" }
model:solve{ to = p.end_time }
