-- Pressing a held spindle down onto a road or drum until it carries a target load.
--
--   local press = require("press")
--   local path = press.path(model, tire.spindle, "press")  -- spindle height follows the path
--   ...                                                    -- inflation, then the contact
--   path:to_load{ load = 3800 }                            -- quasi-static secant steps
--
-- The spindle's downward travel (the depth) follows a path of (time, depth) points,
-- linear between them, held after the last: the pressing extends it step by step, and
-- the depth reached is then kept (a dead axle).
local press = {}

local Path = {}
Path.__index = Path

-- Prescribes the spindle's uy to -depth(t) through the load function 'name'; the path
-- starts at depth 0.
function press.path(model, spindle, name)
  local path = setmetatable({ model = model, spindle = spindle, points = { { 0.0, 0.0 } } }, Path)
  model:load_function{ name = name, fn = function(t) return path:depth(t) end }
  model:prescribe{ node = spindle, dof = "uy", value = -1.0, load_function = name }
  return path
end

-- The depth at time t [m].
function Path:depth(t)
  local points = self.points
  for i = #points, 1, -1 do
    local t1, d1 = points[i][1], points[i][2]
    if t >= t1 then
      local following = points[i + 1]
      if not following then return d1 end
      return d1 + (following[2] - d1) * (t - t1) / (following[1] - t1)
    end
  end
  return 0.0
end

-- One step of dt [s] that moves the spindle linearly to 'depth' [m].
function Path:step_to(depth, dt)
  self.points[#self.points + 1] = { self.model:time() + dt, depth }
  self.model:step{ dt = dt }
end

-- The spindle's vertical force Fz [N] (ISO 8855 wheel axes: the load).
function Path:load()
  return self.model:value{ node = self.spindle, quantity = "spindle_force", component = "fz" }
end

-- Presses from the depth held now to the spindle load args.load [N]: 'ramp_steps' steps of
-- ramp_dt toward the deflection that a vertical stiffness 'stiffness' [N/m] gives, then
-- secant steps of secant_dt on the measured force-deflection curve until the load is met
-- to 'relative' (at most 'max_secant_steps'). An error if it is not. Returns the depth.
function Path:to_load(args)
  local target = args.load
  local relative = args.relative or 1e-3
  local ramp_steps, ramp_dt = args.ramp_steps or 5, args.ramp_dt or 0.1
  self.points[#self.points + 1] = { self.model:time(), self:depth(self.model:time()) }
  -- A first guess: a passenger tire's vertical stiffness, about 170 N/mm.
  local guess = target / (args.stiffness or 170e3)
  for k = 1, ramp_steps do self:step_to(guess * k / ramp_steps, ramp_dt) end
  local previous_depth, previous_load = 0.0, 0.0
  for _ = 1, args.max_secant_steps or 8 do
    local depth, load = self:depth(self.model:time()), self:load()
    if math.abs(load - target) < relative * target then break end
    local stiffness = (load - previous_load) / (depth - previous_depth)
    previous_depth, previous_load = depth, load
    self:step_to(depth + (target - load) / stiffness, args.secant_dt or 0.05)
  end
  if math.abs(self:load() - target) > relative * target then
    error(string.format("pressing did not reach the load %g N (spindle force %g N)", target, self:load()))
  end
  return self:depth(self.model:time())
end

return press
