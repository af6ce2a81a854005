-- The drum of a drum-cleat rig: its turn as the drum surface of the model drives it (at rest
-- until 'start', a spin-up of the surface speed over 'spin_up_time', then the full speed),
-- the times the cleat passes under the tire on top of the drum, and the time step schedule
-- around those passages. The spin-up is linear (ramp = "linear", the default) or rises as
-- (1 - cos) (ramp = "cosine": without the jerk that leaves a tire ringing), as the drum
-- surface's own `speed`, `ramp_time` and `ramp` make it turn: the angles and speeds are the
-- surface's motion itself (tirefe.spin_up), so a deck plans its steps on the drum it runs.
--
--   local drum = require("drum")
--   local rig = drum.rig{ diameter = 1.7, speed = 51.3 / 3.6, start = 2.0, spin_up_time = 4.0 }
--   local passages = rig:passages{ cleat_angle = -math.pi / 2, cleat_length = 0.66, end_time = 8.0 }
--   local time_step = rig:time_step{ passages = passages, dt = 5e-4, dt_max = 2e-3, dt_cleat = 2.5e-4,
--                                    ring_time = 0.15 }
-- The angles are those the model's drum surface turns through with speed = -rig.omega,
-- ramp_time = spin_up_time, ramp = rig.ramp and start_time = start (its history channel
-- _surface_angle), or by a load function of -rig:angle(t);
-- the passages are needed before the run, to plan its steps, so they are computed here.
local drum = {}

local Rig = {}
Rig.__index = Rig

-- The rig from its drum diameter [m], final surface speed [m/s], spin-up start and time [s]
-- and the spin-up's shape (ramp: "linear" or "cosine").
function drum.rig(args)
  local ramp = args.ramp or "linear"
  if ramp ~= "linear" and ramp ~= "cosine" then
    error(string.format("drum.rig: ramp = '%s' is no spin-up: give \"linear\" or \"cosine\"", tostring(ramp)), 2)
  end
  local rig = setmetatable({ radius = args.diameter / 2, speed = args.speed, start = args.start,
                             spin_up_time = args.spin_up_time, ramp = ramp }, Rig)
  rig.omega = rig.speed / rig.radius  -- drum spin at full speed [rad/s]
  return rig
end

-- The value and rate at time t of a motion whose rate rises to 'rate' by the rig's spin-up.
function Rig:spin_up(rate, t)
  return tirefe.spin_up{ rate = rate, ramp_time = self.spin_up_time, start_time = self.start, ramp = self.ramp,
                         time = t }
end

-- The drum's clockwise angle at time t [rad].
function Rig:angle(t)
  local angle = self:spin_up(self.omega, t)
  return angle
end

-- The time at which the drum has turned through 'angle' clockwise (the inverse of Rig:angle):
-- by bisection during the spin-up (the angle rises monotonically), at full speed after it.
function Rig:time_at_angle(angle)
  local full_speed = self.start + self.spin_up_time
  local ramp_angle = self:angle(full_speed)
  if angle > ramp_angle then return full_speed + (angle - ramp_angle) / self.omega end
  local low, high = self.start, full_speed
  for _ = 1, 60 do
    local middle = 0.5 * (low + high)
    if self:angle(middle) < angle then low = middle else high = middle end
  end
  return 0.5 * (low + high)
end

-- The drum's surface speed at time t [m/s].
function Rig:surface_speed(t)
  local _, speed = self:spin_up(self.speed, t)
  return speed
end

-- The passages of a cleat (middle at 'cleat_angle' from +x at rest, 'cleat_length' along the
-- surface) under the top of the drum (the middle of the contact patch) before 'end_time':
-- a list of { on = time the leading edge arrives, off = time the trailing edge leaves }.
function Rig:passages(args)
  local half_angle = args.cleat_length / (2 * self.radius)
  if half_angle >= math.pi / 2 then error("parameter cleat_length is too long for the drum", 0) end
  local lead = (args.cleat_angle - half_angle) - math.pi / 2  -- clockwise turn that brings the leading edge to the top
  local trail = (args.cleat_angle + half_angle) - math.pi / 2
  while lead < 0 do lead, trail = lead + 2 * math.pi, trail + 2 * math.pi end
  local passages = {}
  while self:time_at_angle(lead) < args.end_time do
    passages[#passages + 1] = { on = self:time_at_angle(lead), off = self:time_at_angle(trail) }
    lead, trail = lead + 2 * math.pi, trail + 2 * math.pi
  end
  return passages
end

-- The end of the first passage at full speed: when its trailing edge has left the top.
function Rig:first_full_speed_passage_end(args)
  local half_angle = args.cleat_length / (2 * self.radius)
  local lead = (args.cleat_angle - half_angle) - math.pi / 2
  while lead < 0 do lead = lead + 2 * math.pi end
  while self:time_at_angle(lead) < self.start + self.spin_up_time do lead = lead + 2 * math.pi end
  return self:time_at_angle(lead + 2 * half_angle)
end

-- Refuses a run (cleat.end_time) that ends before its first passage at full speed has rung
-- for ring_time: the summary reads one. The error names the end_time needed.
function Rig:require_full_speed_passage(cleat, ring_time)
  local needed = self:first_full_speed_passage_end(cleat) + ring_time
  if needed > cleat.end_time + 1e-9 then
    error(string.format("parameter end_time = %g s ends before the first cleat passage at full speed has rung out: "
                        .. "give end_time >= %.3f s", cleat.end_time, needed), 0)
  end
end

-- The time of one turn at full speed, pi D / v [s]: the cleat's period.
function Rig:turn_time()
  return 2 * math.pi * self.radius / self.speed
end

-- The passages a summary reads: the last two at full speed (from start + spin_up_time on)
-- that have rung for ring_time by end_time, in time order; one or none if there are fewer.
-- Two, because a passage's peaks depend on where the tread nodes meet the cleat, which
-- changes from one passage to the next (docs/drum_cleat.md, "Two passages").
function Rig:read_passages(passages, ring_time, end_time)
  local rung = {}
  for _, passage in ipairs(passages) do
    if passage.on >= self.start + self.spin_up_time and passage.off + ring_time <= end_time then
      rung[#rung + 1] = passage
    end
  end
  local read = {}
  for i = math.max(1, #rung - 1), #rung do read[#read + 1] = rung[i] end
  return read
end

-- The time step at time t: dt_cleat through the passages at full speed and the one before
-- them, from 10 ms before each until ring_time after it; elsewhere the step in which a point
-- of the drum surface travels as far as in dt at full speed, up to dt_max. The earlier
-- passages of the spin-up, which nothing reads, take those travel steps too: slower, they
-- are resolved as finely along the drum. A passage carries over to the next ones: with the
-- ringing of the passages before a read one on travel steps, its readings move by up to 5 %
-- and its Fx peak to peak by up to 8 %, and still by 6 % with the one passage before it on
-- fine steps, hence fine steps through every passage at full speed and the one before them.
-- Returns the schedule as a function of t.
function Rig:time_step(args)
  local fine = {}
  for i, passage in ipairs(args.passages) do
    local next_passage = args.passages[i + 1]
    if (next_passage and next_passage.on or passage.on) >= self.start + self.spin_up_time then
      fine[#fine + 1] = { from = passage.on - 0.01, to = passage.off + args.ring_time }
    end
  end
  return function(t)
    for _, span in ipairs(fine) do
      if t > span.from and t < span.to then return args.dt_cleat end
    end
    return math.min(args.dt_max, args.dt * self.speed / math.max(self:surface_speed(t), 1e-9))
  end
end

-- The period of the impacts at full speed: the mean spacing of the times of the largest
-- values (spindle Fz, say) of the passages at full speed that end 10 ms before end_time;
-- also their number. nil if fewer than two.
function Rig:impact_period(passages, time, values, end_time)
  local series = require("series")
  local peaks = {}
  for _, passage in ipairs(passages) do
    if passage.on >= self.start + self.spin_up_time and passage.off + 0.01 <= end_time then
      peaks[#peaks + 1] = series.peak(time, values, passage.on - 0.01, passage.off + 0.01)
    end
  end
  return series.mean_spacing(peaks), #peaks
end

return drum
