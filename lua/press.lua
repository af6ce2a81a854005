-- Pressing a held spindle down onto a road or drum: to a depth, along a load-deflection
-- curve, or until it carries a load.
--
--   local press = require("press")
--   local path = press.path(model, tire.spindle, "press")  -- spindle height follows the path
--   ...                                                    -- inflation, then the contact
--   path:move_to(0.020, 4, 0.25)                           -- to a depth, in 4 steps of 0.25 s
--   path:load_curve({ 0.005, 0.010 }, 0.001)               -- the loads at depths on the way
--   path:to_load{ load = 3800 }                            -- quasi-static secant steps
--
-- The spindle's downward travel (the depth) follows a path of (time, depth) points, linear
-- between them and held after the last (a dead axle). Each move is a table load function
-- of its own ('name', 'name_2', ...) prescribing uy = -depth: no Lua runs while the model
-- steps, so a path serves threaded vehicle runs and restarts alike.
local press = {}

local Path = {}
Path.__index = Path

-- Holds the spindle's uy at depth 0 from the start on, through the load function 'name'.
function press.path(model, spindle, name)
  local path = setmetatable({ model = model, spindle = spindle, name = name, moves = 0, points = { { 0.0, 0.0 } } },
                            Path)
  path:prescribe{ { 0.0, 0.0 } }
  return path
end

-- The spindle's uy = -depth on a table of (time, depth) points: a load function of its own.
function Path:prescribe(points)
  self.moves = self.moves + 1
  local name = self.moves == 1 and self.name or self.name .. "_" .. self.moves
  self.model:load_function{ name = name, points = points }
  self.model:prescribe{ node = self.spindle, dof = "uy", value = -1.0, load_function = name }
end

-- The depth at time t [m] (default: now).
function Path:depth(t)
  t = t or self.model:time()
  local points = self.points
  for i = #points, 1, -1 do
    local t1, d1 = points[i][1], points[i][2]
    if t >= t1 then
      local following = points[i + 1]
      if not following then return d1 end
      return d1 + (t - t1) / (following[1] - t1) * (following[2] - d1)
    end
  end
  return 0.0
end

-- The spindle's vertical force Fz [N] (ISO 8855 wheel axes: the load).
function Path:load()
  return self.model:value{ node = self.spindle, quantity = "spindle_force", component = "fz" }
end

-- Moves the spindle linearly from the depth held now to 'depth' [m] in 'steps' steps of
-- dt [s] (quasi-static, or dynamic if the model has an integrator). Returns the path, so
-- that path:move_to(...):load() reads the load there; a deck to be restarted reads none.
function Path:move_to(depth, steps, dt)
  local start = self.model:time()
  self:extend(start, start + steps * dt, depth)
  self.model:solve{ to = start + steps * dt, dt = dt }
  return self
end

-- The loads [N] at 'depths' [m], reached in turn on one straight move from the depth held
-- now to the last of them, over 1 s in steps of 'step' [m] of depth: a load-deflection curve.
function Path:load_curve(depths, step)
  local start, deepest = self.model:time(), depths[#depths]
  local from = self:extend(start, start + 1.0, deepest)
  local loads = {}
  for i, depth in ipairs(depths) do
    self.model:solve{ to = start + (depth - from) / (deepest - from), dt = step / (deepest - from) }
    loads[i] = self:load()
  end
  return loads
end

-- Extends the path from (start, the depth held) to (finish, depth); returns the depth held.
function Path:extend(start, finish, depth)
  local from = { start, self:depth(start) }
  if start > self.points[#self.points][1] then self.points[#self.points + 1] = from end
  self.points[#self.points + 1] = { finish, depth }
  self:prescribe{ from, { finish, depth } }
  return from[2]
end

-- Presses from depth 0 to the spindle load args.load [N] and returns the depth reached.
-- First the depths of args.schedule ({ { depth, steps }, ... }, each reached in 'steps'
-- steps of args.dt, default 0.1 s); without one, the deflection a vertical stiffness
-- args.stiffness (default: a passenger tire's, 170 N/mm) gives, in 5 steps. Then
-- corrections on the measured load-depth curve, each in args.correction_steps (1) steps of
-- args.correction_dt (0.05 s): secant steps through the last two points (the first from
-- depth 0 at no load), or with update = "chord" the depth scaled by target / load (the
-- chord through the origin). They stop once the load is met to args.relative (1e-3), an
-- error if it is not after args.corrections (8); with relative = false all the corrections
-- are taken and the deck checks the load. path.curve holds the (depth, load) points.
function Path:to_load(args)
  local target, relative = args.load, args.relative
  if relative == nil then relative = 1e-3 end
  local schedule = args.schedule or { { target / (args.stiffness or 170e3), 5 } }
  local curve = { { 0.0, 0.0 } }
  for _, move in ipairs(schedule) do
    curve[#curve + 1] = { move[1], self:move_to(move[1], move[2], args.dt or 0.1):load() }
  end
  local function met(load) return relative and math.abs(load - target) < relative * target end
  for _ = 1, args.corrections or 8 do
    local depth, load = curve[#curve][1], curve[#curve][2]
    if met(load) then break end
    local next_depth
    if args.update == "chord" then
      next_depth = depth * target / load
    else
      local before = curve[#curve - 1]
      next_depth = depth + (target - load) / ((load - before[2]) / (depth - before[1]))
    end
    local steps, dt = args.correction_steps or 1, args.correction_dt or 0.05
    curve[#curve + 1] = { next_depth, self:move_to(next_depth, steps, dt):load() }
  end
  self.curve = curve
  local depth, load = curve[#curve][1], curve[#curve][2]
  if relative and not met(load) then
    error(string.format("pressing did not reach the load %g N (spindle force %g N)", target, load))
  end
  return depth
end

return press
