// Tests of the deck library modules in lua/ (drum, press, series, rolling, stepping, cleat_summary,
// guard), each through a small self-checking deck run in the sandbox.
#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <sstream>

#include "contact/rigid_surface.hpp"
#include "deck_support.hpp"
#include "macros/macro_table.hpp"
#include "test_support.hpp"
#include "vehicle/tire_on_road.hpp"

TEST_CASE("lua/drum.lua: the drum's turn, the cleat passages and the step schedule", "[lua][modules][drum]") {
  // The drum-cleat rig with a 0.5 s spin-up: omega = 14.25 m/s / 0.85 m = 16.7647 rad/s; the
  // cleat's middle at the bottom, its leading edge reaches the top after pi - 0.66 / 1.7 rad.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("drum_deck.lua", R"(
local rig = require("drum").rig{ diameter = 1.7, speed = 51.3 / 3.6, start = 2.0, spin_up_time = 0.5 }
tirefe.check{ name = "omega [rad/s]", value = rig.omega, expected = 16.764705882352942, relative = 1e-14 }
tirefe.check{ name = "at rest before the start", value = rig:angle(1.5), expected = 0, tolerance = 0 }
tirefe.check{ name = "angle in the spin-up [rad]", value = rig:angle(2.25), expected = 1.0477941176470587, relative = 1e-14 }
tirefe.check{ name = "angle at full speed [rad]", value = rig:angle(3.0), expected = 12.573529411764703, relative = 1e-14 }
tirefe.check{ name = "time_at_angle inverts angle, spin-up [s]", value = rig:time_at_angle(rig:angle(2.3)),
              expected = 2.3, tolerance = 1e-12 }
tirefe.check{ name = "time_at_angle inverts angle, full speed [s]", value = rig:time_at_angle(rig:angle(2.9)),
              expected = 2.9, tolerance = 1e-12 }
tirefe.check{ name = "surface speed halfway up [m/s]", value = rig:surface_speed(2.25), expected = 7.125, relative = 1e-14 }
local cleat = { cleat_angle = -math.pi / 2, cleat_length = 0.66, end_time = 3.5 }
local passages = rig:passages(cleat)
tirefe.check{ name = "passages before 3.5 s", value = #passages, expected = 3, tolerance = 0 }
tirefe.check{ name = "first passage on [s]", value = passages[1].on, expected = 2.4052596097155003, tolerance = 1e-12 }
tirefe.check{ name = "first passage off [s]", value = passages[1].off, expected = 2.4588585193068164, tolerance = 1e-12 }
tirefe.check{ name = "second passage on [s]", value = passages[2].on, expected = 2.789021843273963, tolerance = 1e-12 }
tirefe.check{ name = "full speed: a turn between passages = pi D / v [s]", value = passages[3].on - passages[2].on,
              expected = math.pi * 1.7 / (51.3 / 3.6), relative = 1e-12 }
tirefe.check{ name = "full speed: the cleat passes in its length / v [s]", value = passages[2].off - passages[2].on,
              expected = 0.66 / (51.3 / 3.6), relative = 1e-12 }
tirefe.check{ name = "first full-speed passage ends [s]", value = rig:first_full_speed_passage_end(cleat),
              expected = 2.835337632747647, tolerance = 1e-12 }
local step = rig:time_step{ passages = passages, dt = 5e-4, dt_max = 2e-3, dt_cleat = 2.5e-4, ring_time = 0.15 }
tirefe.check{ name = "slow drum: dt_max [s]", value = step(2.1), expected = 2e-3, tolerance = 0 }
tirefe.check{ name = "spin-up: dt x full speed / speed [s]", value = step(2.2), expected = 1.25e-3, relative = 1e-12 }
tirefe.check{ name = "10 ms before the passage before full speed: dt_cleat [s]", value = step(2.3955),
              expected = 2.5e-4, tolerance = 0 }
tirefe.check{ name = "10 ms before a full-speed passage: dt_cleat [s]", value = step(2.7795), expected = 2.5e-4,
              tolerance = 0 }
-- The 4 s spin-up: five passages in it (from 3.146 s), the last at 5.648-5.698 s.
local slow = require("drum").rig{ diameter = 1.7, speed = 51.3 / 3.6, start = 2.0, spin_up_time = 4.0 }
local slow_passages = slow:passages{ cleat_angle = -math.pi / 2, cleat_length = 0.66, end_time = 8.0 }
local slow_step = slow:time_step{ passages = slow_passages, dt = 5e-4, dt_max = 2e-3, dt_cleat = 2.5e-4, ring_time = 0.15 }
tirefe.check{ name = "first passage of the spin-up: dt x full speed / speed [s]", value = slow_step(3.2),
              expected = 5e-4 * 4.0 / 1.2, relative = 1e-12 }
tirefe.check{ name = "fourth passage of the spin-up: dt x full speed / speed [s]", value = slow_step(5.22),
              expected = 5e-4 * 4.0 / 3.22, relative = 1e-12 }
tirefe.check{ name = "the passage before full speed: dt_cleat [s]", value = slow_step(5.66), expected = 2.5e-4,
              tolerance = 0 }
tirefe.check{ name = "its ringing: dt_cleat [s]", value = slow_step(5.84), expected = 2.5e-4, tolerance = 0 }
tirefe.check{ name = "ring_time after a passage: dt_cleat [s]", value = step(2.98), expected = 2.5e-4, tolerance = 0 }
tirefe.check{ name = "full speed between passages: dt [s]", value = step(3.1), expected = 5e-4, relative = 1e-14 }
local read = rig:read_passages(passages, 0.15, 3.2)
tirefe.check{ name = "one full-speed passage rung out by 3.2 s", value = #read, expected = 1, tolerance = 0 }
tirefe.check{ name = "it is the second passage [s]", value = read[1].on, expected = passages[2].on, tolerance = 0 }
read = rig:read_passages(passages, 0.15, 3.5)
tirefe.check{ name = "by 3.5 s: the last two, in time order [s]", value = read[2].on - read[1].on,
              expected = passages[3].on - passages[2].on, tolerance = 0 }
tirefe.check{ name = "none before the first has rung out", value = #rig:read_passages(passages, 0.15, 2.9),
              expected = 0, tolerance = 0 }
-- Made-up Fz: a spike 20 ms into each passage.
local time, fz = {}, {}
for k = 0, 1500 do
  time[#time + 1] = 2.0 + k * 1e-3
  fz[#fz + 1] = 0
  for _, passage in ipairs(passages) do
    if math.abs(time[#time] - (passage.on + 0.02)) < 5e-4 then fz[#fz] = 1 end
  end
end
local period, count = rig:impact_period(passages, time, fz, 3.5)
tirefe.check{ name = "impact period from the Fz peaks [s]", value = period, expected = passages[3].on - passages[2].on,
              tolerance = 1e-3 }
tirefe.check{ name = "full-speed passages read", value = count, expected = 2, tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 30);
}

TEST_CASE("lua/drum.lua: the (1 - cos) spin-up, its angle, speed and inverse", "[lua][modules][drum]") {
  // omega = 16.7647 rad/s over a 0.15 s ramp from 3 s: the angle at the ramp's end is
  // omega ramp / 2 = 1.2573529 rad, as the linear ramp's; the speed halfway up is v / 2.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("cosine_drum_deck.lua", R"(
local drum = require("drum")
local rig = drum.rig{ diameter = 1.7, speed = 51.3 / 3.6, start = 3.0, spin_up_time = 0.15, ramp = "cosine" }
tirefe.check{ name = "at rest before the start", value = rig:angle(2.9), expected = 0, tolerance = 0 }
tirefe.check{ name = "angle at the ramp's end [rad]", value = rig:angle(3.15), expected = 0.5 * rig.omega * 0.15,
              relative = 1e-14 }
tirefe.check{ name = "angle at full speed [rad]", value = rig:angle(4.0), expected = rig.omega * (1.0 - 0.075),
              relative = 1e-14 }
tirefe.check{ name = "surface speed halfway up [m/s]", value = rig:surface_speed(3.075), expected = 51.3 / 3.6 / 2,
              relative = 1e-14 }
local h = 1e-6
for _, t in ipairs{ 3.01, 3.075, 3.14, 3.5 } do
  tirefe.check{ name = "d angle / dt = surface speed / radius at " .. t .. " s [rad/s]",
                value = (rig:angle(t + h) - rig:angle(t - h)) / (2 * h), expected = rig:surface_speed(t) / 0.85,
                relative = 1e-7 }
end
tirefe.check{ name = "time_at_angle inverts angle, spin-up [s]", value = rig:time_at_angle(rig:angle(3.05)),
              expected = 3.05, tolerance = 1e-12 }
tirefe.check{ name = "time_at_angle inverts angle, full speed [s]", value = rig:time_at_angle(rig:angle(3.9)),
              expected = 3.9, tolerance = 1e-12 }
local ok, message = pcall(drum.rig, { diameter = 1.7, speed = 1, start = 0, spin_up_time = 1, ramp = "smooth" })
tirefe.check{ name = "an unknown ramp is refused", value = ok and 1 or 0, expected = 0, tolerance = 0 }
tirefe.check{ name = "naming the choices", value = message:find('give "linear" or "cosine"', 1, true) and 1 or 0,
              expected = 1, tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 12);
}

TEST_CASE("lua/series.lua and lua/rolling.lua: windows, peaks, rises, means, rolling radius", "[lua][modules]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("series_deck.lua", R"(
local series = require("series")
local rolling = require("rolling")
local time = { 1.0, 2.0, 3.0, 4.0, 5.0 }
local fz = { 10.0, 30.0, -5.0, 30.0, 20.0 }
local low, high = series.range(time, fz, 2.0, 4.0)
tirefe.check{ name = "range low, window ends included", value = low, expected = -5, tolerance = 0 }
tirefe.check{ name = "range high", value = high, expected = 30, tolerance = 0 }
local peak_time, peak = series.peak(time, fz, 1.5, 5.0)
tirefe.check{ name = "peak: the first of equal maxima [s]", value = peak_time, expected = 2.0, tolerance = 0 }
tirefe.check{ name = "peak value", value = peak, expected = 30, tolerance = 0 }
tirefe.check{ name = "no peak in an empty window", value = series.peak(time, fz, 6, 7) == nil and 1 or 0, expected = 1 }
-- A load that drops below 0 and rises back through 20 between t = 3 (-5) and t = 4 (30).
tirefe.check{ name = "rise through 20 after a drop below 0 [s]", value = series.rise(time, fz, 1.0, 5.0, 20, 0),
              expected = 3 + 25 / 35, relative = 1e-14 }
tirefe.check{ name = "no rise without the drop in the window", value = series.rise(time, fz, 3.5, 5.0, 20, 0) == nil
              and 1 or 0, expected = 1 }
tirefe.check{ name = "no rise through a level never reached", value = series.rise(time, fz, 1.0, 5.0, 40, 0) == nil
              and 1 or 0, expected = 1 }
tirefe.check{ name = "a drop level above the rise is refused", value = pcall(series.rise, time, fz, 1, 5, 20, 25) and 1
              or 0, expected = 0 }
tirefe.check{ name = "mean over from < t <= to", value = series.mean(time, fz, 1.0, 3.0, function(v) return v end),
              expected = 12.5, tolerance = 1e-15 }
tirefe.check{ name = "mean spacing of peak times [s]", value = series.mean_spacing{ 2.0, 2.375, 2.75, 3.125 },
              expected = 0.375, tolerance = 1e-15 }
tirefe.check{ name = "value between samples, linear", value = series.at(time, fz, 2.25), expected = 21.25, tolerance = 1e-15 }
tirefe.check{ name = "value at a sample", value = series.at(time, fz, 5.0), expected = 20, tolerance = 0 }
tirefe.check{ name = "no value outside the series", value = series.at(time, fz, 5.5) == nil and 1 or 0, expected = 1,
              tolerance = 0 }
tirefe.check{ name = "rolling radius = speed / spin, averaged [m]",
              value = rolling.radius{ time = time, spin = { 10, 20, 40, 50, 60 }, speed = 2.0, from = 1.0, to = 3.0 },
              expected = 0.075, tolerance = 1e-15 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 15);
}

TEST_CASE("lua/press.lua presses a tire onto a road to a load; rolling.lua's tread ring", "[lua][modules][press]") {
  // The 145 SR-12 inflated on a held hub over a flat road, pressed to 2500 N by secant steps.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("press_deck.lua", R"(
local tp = require("tires.145SR12")
tp.elements = 60
local model = tirefe.model{ title = "press" }
local tire, level = require("tire_on_road").inflated(model, tp)
-- The inflated, unloaded tread nodes form a regular polygon of 60 sides about the spindle.
local sx = model:value{ node = tire.spindle, dof = "ux", quantity = "position" }
local sy = model:value{ node = tire.spindle, dof = "uy", quantity = "position" }
local r = 0
for _, node in ipairs(tire.tread) do
  local x = model:value{ node = node, dof = "ux", quantity = "position" }
  local y = model:value{ node = node, dof = "uy", quantity = "position" }
  r = r + math.sqrt((x - sx) ^ 2 + (y - sy) ^ 2) / #tire.tread
end
tirefe.check{ name = "tread ring of the round tire = 2 n r sin(pi / n) [m]",
              value = require("rolling").tread_circumference(model, tire.tread),
              expected = 2 * #tire.tread * r * math.sin(math.pi / #tire.tread), relative = 1e-9 }
model:surface{ name = "road", type = "flat", point = { 0, level } }
model:tire_contact{ surface = "road", friction = 0.5 }
local path = require("press").path(model, tire.spindle, "press")
local depth = path:to_load{ load = 2500 }
tirefe.check{ name = "pressed to the load [N]", value = path:load(), expected = 2500, tolerance = 2.5 }
tirefe.check{ name = "the spindle went down by the depth returned [m]",
              value = -model:value{ node = tire.spindle, dof = "uy" }, expected = depth, relative = 1e-12 }
tirefe.check{ name = "the depth is a tire's deflection at that load, 10-20 mm [m]", value = depth, expected = 0.015,
              tolerance = 0.005 }
model:solve{ to = model:time() + 0.2, dt = 0.1 }
tirefe.check{ name = "the depth is then held [m]", value = path:depth(model:time()), expected = depth, tolerance = 0 }
tirefe.check{ name = "and the load with it [N]", value = path:load(), expected = 2500, tolerance = 2.5 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 6);
}

TEST_CASE("lua/press.lua: moves to depths, a load-deflection curve, a depth schedule with chord corrections",
          "[lua][modules][press]") {
  // The 145 SR-12 (60 wedges) inflated on a held hub over a frictionless flat road.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("press_moves_deck.lua", R"(
local press = require("press")
-- A frictionless road: the quasi-static load depends on the depth alone, not on the way there.
local function pressed_tire(title)
  local tp = require("tires.145SR12")
  tp.elements = 60
  local model = tirefe.model{ title = title }
  local tire, level = require("tire_on_road").inflated(model, tp)
  model:surface{ name = "road", type = "flat", point = { 0, level } }
  model:tire_contact{ surface = "road", friction = 0 }
  return model, press.path(model, tire.spindle, "press"), tire
end

-- A move: linear in time from the depth held, held after it.
local model, path, tire = pressed_tire("move")
local load = path:move_to(0.008, 4, 0.25):load()
tirefe.check{ name = "move: the spindle at -depth [m]", value = model:value{ node = tire.spindle, dof = "uy" },
              expected = -0.008, tolerance = 0 }
tirefe.check{ name = "move: 4 steps of 0.25 s from 1 s [s]", value = model:time(), expected = 2.0, tolerance = 0 }
tirefe.check{ name = "move: depth halfway [m]", value = path:depth(1.5), expected = 0.004, relative = 1e-15 }
tirefe.check{ name = "move: held before it [m]", value = path:depth(0.5), expected = 0, tolerance = 0 }

-- A load-deflection curve on one straight move: its loads are the moves' loads.
local curve_model, curve_path = pressed_tire("curve")
local loads = curve_path:load_curve({ 0.004, 0.008, 0.012 }, 0.001)
tirefe.check{ name = "curve: three loads", value = #loads, expected = 3, tolerance = 0 }
tirefe.check{ name = "curve: the load at 8 mm = the move's [N]", value = loads[2], expected = load, relative = 1e-6 }
tirefe.check{ name = "curve: a tire's stiffness, 150-200 N/mm [N/m]", value = (loads[3] - loads[1]) / 0.008,
              expected = 175e3, tolerance = 25e3 }
tirefe.check{ name = "curve: ends at the last depth [m]", value = curve_path:depth(), expected = 0.012, tolerance = 0 }
tirefe.check{ name = "curve: 1 s long [s]", value = curve_model:time(), expected = 2.0, tolerance = 1e-12 }

-- To a load by a depth schedule and two chord corrections, taken whatever the load.
local chord_model, chord_path = pressed_tire("chord")
local depth = chord_path:to_load{ load = 2500, schedule = { { 0.006, 2 }, { 0.010, 2 } }, dt = 0.25, update = "chord",
                                  corrections = 2, correction_steps = 2, correction_dt = 0.1, relative = false }
local curve = chord_path.curve
tirefe.check{ name = "chord: origin, schedule and corrections", value = #curve, expected = 5, tolerance = 0 }
tirefe.check{ name = "chord: the schedule's last depth [m]", value = curve[3][1], expected = 0.010, tolerance = 0 }
tirefe.check{ name = "chord: depth x target / load [m]", value = curve[5][1],
              expected = curve[4][1] * 2500 / curve[4][2], tolerance = 0 }
tirefe.check{ name = "chord: returns the last depth [m]", value = depth, expected = curve[5][1], tolerance = 0 }
tirefe.check{ name = "chord: the load read after the move [N]", value = chord_path:load(), expected = curve[5][2],
              tolerance = 0 }
tirefe.check{ name = "chord: 1 s inflation, the schedule, two corrections [s]", value = chord_model:time(),
              expected = 1 + 4 * 0.25 + 2 * 2 * 0.1, relative = 1e-15 }
tirefe.check{ name = "chord: within 1 % of the load [N]", value = chord_path:load(), expected = 2500, relative = 0.01 }

-- Secant steps to a load that cannot be met in one correction: an error.
local _, short_path = pressed_tire("short")
local ok, message = pcall(short_path.to_load, short_path, { load = 2500, corrections = 0 })
tirefe.check{ name = "no correction left: an error", value = ok and 1 or 0, expected = 0, tolerance = 0 }
tirefe.check{ name = "the error names the load", value = message:find("did not reach the load 2500 N") and 1 or 0,
              expected = 1, tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 18);
}

TEST_CASE("lua/stepping.lua steps on a schedule, lands on the end and records channels", "[lua][modules]") {
  // A stand-in model whose step reports two Newton iterations and cuts every third step.
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("stepping_deck.lua", R"(
local model = { t = 0.0, calls = 0 }
function model:time() return self.t end
function model:step(args)
  self.t, self.calls = self.t + args.dt, self.calls + 1
  local cut = self.calls % 3 == 0 and 1 or 0
  return { steps = 1 + cut, newton_iterations = 2, cuts = cut }
end
local record, totals = require("stepping").run(model, {
  to = 1.05, time_step = function(t) return t < 0.5 and 0.1 or 0.2 end,
  channels = { twice = function() return 2 * model.t end } })
-- Five steps of 0.1 to 0.5, then 0.7, 0.9 and a last one shortened to land on 1.05.
tirefe.check{ name = "steps", value = #record.time, expected = 8, tolerance = 0 }
tirefe.check{ name = "ends on 'to' [s]", value = record.time[#record.time], expected = 1.05, tolerance = 1e-12 }
tirefe.check{ name = "channel read after each step", value = record.twice[#record.twice], expected = 2.1,
              tolerance = 1e-12 }
tirefe.check{ name = "Newton iterations summed", value = totals.newton, expected = 16, tolerance = 0 }
tirefe.check{ name = "cuts summed", value = totals.cuts, expected = 2, tolerance = 0 }
tirefe.check{ name = "steps include the cut pieces", value = totals.steps, expected = 10, tolerance = 0 }
tirefe.check{ name = "first step 0.1 s [s]", value = record.time[1], expected = 0.1, tolerance = 1e-15 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 7);
}

TEST_CASE("model:history_values returns a channel's values, one per step, as model:value read them",
          "[lua][macros][output]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("history_values_deck.lua", R"(
-- A cantilever under a tip load growing with time (the default ramp), quasi-static.
local model = tirefe.model{ title = "history values" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:load{ node = b, fy = -0.01 }
model:history{ name = "tip_uy", node = b, dof = "uy" }
tirefe.check{ name = "no values before the first step", value = #model:history_values{ name = "tip_uy" },
              expected = 0, tolerance = 0 }
local read = {}
for k = 1, 5 do
  model:step{ dt = 0.1 }
  read[k] = model:value{ node = b, dof = "uy" }
end
local time, tip = model:history_values{ name = "time" }, model:history_values{ name = "tip_uy" }
tirefe.check{ name = "one value per step", value = #tip, expected = 5, tolerance = 0 }
tirefe.check{ name = "their times [s]", value = time[5], expected = 0.5, tolerance = 1e-12 }
local differing = 0
for k = 1, 5 do if tip[k] ~= read[k] then differing = differing + 1 end end
tirefe.check{ name = "the values model:value read after each step, bit for bit", value = differing, expected = 0,
              tolerance = 0 }
-- One linear beam element with one-point integration: P L^3 / (4 EI) + P L / GA, with
-- P = 0.01 N x 0.5 at t = 0.5 s (small: the linear answer).
tirefe.check{ name = "the tip under the load, one element's [m]", value = tip[5], expected = -0.005 / 4 - 0.005 / 1e5,
              relative = 1e-3 }
local ok, message = pcall(model.history_values, model, { name = "tip_ux" })
local named = not ok and message:find("no history channel 'tip_ux'", 1, true) and message:find("tip_uy", 1, true)
tirefe.check{ name = "an unknown channel is refused, naming the channels", value = named and 1 or 0, expected = 1,
              tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 6);
}

TEST_CASE("lua/stepping.lua sets the integrator by name", "[lua][modules]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("integrator_deck.lua", R"(
-- The integrator by name: a stand-in model keeps what it was given.
local given
local stand_in = { integrator = function(_, args) given = args end }
local stepping = require("stepping")
stepping.integrator(stand_in, { type = "newmark", gamma = 0.6, alpha = -0.1 })
tirefe.check{ name = "Newmark: beta = (gamma + 1/2)^2 / 4", value = given.beta, expected = 0.3025, relative = 1e-15 }
tirefe.check{ name = "Newmark: gamma as given", value = given.gamma, expected = 0.6, tolerance = 0 }
stepping.integrator(stand_in, { type = "hht", alpha = -0.1, gamma = 0.6 })
tirefe.check{ name = "HHT: alpha as given", value = given.alpha, expected = -0.1, tolerance = 0 }
tirefe.check{ name = "HHT: the scheme's own gamma", value = given.gamma == nil and 1 or 0, expected = 1, tolerance = 0 }
local ok, message = pcall(stepping.integrator, stand_in, { type = "euler" })
local refused = not ok and message:find("not 'euler'", 1, true)
tirefe.check{ name = "another name is an error naming it", value = refused and 1 or 0, expected = 1, tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 5);
}

TEST_CASE("lua/cleat_summary.lua reads the last two full-speed passages of made-up forces", "[lua][modules][drum]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("cleat_summary_deck.lua", R"(
-- Made-up spindle forces of a 0.5 s spin-up rig: from each passage's first touch Fx rings at
-- 35 Hz (damping ratio 0.1) and Fz at 85 Hz (0.05), each gone by the next passage; the tire
-- rolls on a radius of 0.27 m, its turn recorded.
local rig = require("drum").rig{ diameter = 1.7, speed = 51.3 / 3.6, start = 2.0, spin_up_time = 0.5 }
local passages = rig:passages{ cleat_angle = -math.pi / 2, cleat_length = 0.66, end_time = 3.5 }
local lag = require("cleat_ringing").reach / rig.speed
local function ring(t, f, zeta, amplitude)
  local value = 0
  for _, passage in ipairs(passages) do
    local tau = t - (passage.on - lag)
    if tau > 0 then
      value = value + amplitude * math.exp(-zeta * 2 * math.pi * f * tau) * math.sin(2 * math.pi * f * tau)
    end
  end
  return value
end
local record = { time = {}, fx = {}, fz = {}, spin = {}, turn = {} }
for k = 0, 6000 do
  local t = 2.0 + k * 2.5e-4
  record.time[#record.time + 1], record.spin[#record.spin + 1] = t, rig:surface_speed(t) / 0.27
  record.turn[#record.turn + 1] = -rig:angle(t) * 0.85 / 0.27
  record.fx[#record.fx + 1], record.fz[#record.fz + 1] = ring(t, 35, 0.1, -2000), 3800 + ring(t, 85, 0.05, 3000)
end
-- A stand-in model: its results kept, its contact nodes on a regular 100-gon of radius 0.27 m.
local results, contact = {}, {}
for i = 1, 100 do contact[i] = i end
local model = { result = function(_, args) results[args.name] = args.value end,
                value = function(_, args)
                  local angle = 2 * math.pi * args.node / 100
                  return 0.27 * (args.dof == "ux" and math.cos(angle) or math.sin(angle))
                end }
local summary = require("cleat_summary").report{ model = model, rig = rig, passages = passages, record = record,
  ring_time = 0.15, end_time = 3.5, speed_kmh = 51.3, tread = contact, unloaded_radius = 0.2715, deflection = 0.025,
  elements = 100 }
tirefe.check{ name = "the last passage rung out by 3.5 s", value = summary.passage.on, expected = passages[3].on,
              tolerance = 0 }
-- A damped sinusoid's first two extrema, at tan(omega tau) = omega / sigma, give its peak to peak.
local function peak_to_peak(f, zeta, amplitude)
  local omega = 2 * math.pi * f
  local sigma = zeta * omega
  local first = math.atan(omega / sigma) / omega
  local function at(tau) return amplitude * math.exp(-sigma * tau) * math.sin(omega * tau) end
  return math.abs(at(first) - at(first + math.pi / omega))
end
tirefe.check{ name = "Fx peak to peak [N]", value = summary.fx_peak_to_peak, expected = peak_to_peak(35, 0.1, 2000),
              relative = 2e-3 }
tirefe.check{ name = "Fz peak to peak [N]", value = summary.fz_peak_to_peak, expected = peak_to_peak(85, 0.05, 3000),
              relative = 2e-3 }
tirefe.check{ name = "written to the results [N]", value = results.fz_peak_to_peak, expected = summary.fz_peak_to_peak,
              tolerance = 0 }
tirefe.check{ name = "Fx ringing after the cleat [Hz]", value = summary.ringing.fx_leaving.pencil_frequency,
              expected = 35, relative = 0.01 }
tirefe.check{ name = "Fz ringing after the cleat [Hz]", value = summary.ringing.fz_leaving.pencil_frequency,
              expected = 85, relative = 0.01 }
tirefe.check{ name = "no measured column given", value = summary.measured == nil and 1 or 0, expected = 1,
              tolerance = 0 }
-- The passage before the last: the same made-up ringing, read alike and written with "before_".
tirefe.check{ name = "the passage before [s]", value = summary.before.passage.on, expected = passages[2].on,
              tolerance = 0 }
tirefe.check{ name = "its Fx peak to peak [N]", value = summary.before.fx_peak_to_peak,
              expected = peak_to_peak(35, 0.1, 2000), relative = 2e-3 }
tirefe.check{ name = "its Fz ringing after the cleat [Hz]", value = summary.before.ringing.fz_leaving.pencil_frequency,
              expected = 85, relative = 0.01 }
tirefe.check{ name = "written to the results as before_ [N]", value = results.before_fx_peak_to_peak,
              expected = summary.before.fx_peak_to_peak, tolerance = 0 }
tirefe.check{ name = "its window written as before_ [s]", value = results.before_fx_leaving_from_s,
              expected = summary.before.ringing.fx_leaving.from, tolerance = 0 }
-- Both passages: the mean peak to peak, and a drum's turn apart, 100 * 0.85 / 0.27 node spacings.
tirefe.check{ name = "mean Fx peak to peak of both [N]", value = results.mean_fx_peak_to_peak,
              expected = (summary.fx_peak_to_peak + summary.before.fx_peak_to_peak) / 2, relative = 1e-15 }
tirefe.check{ name = "mean Fz peak to peak of both [N]", value = results.mean_fz_peak_to_peak,
              expected = (summary.fz_peak_to_peak + summary.before.fz_peak_to_peak) / 2, relative = 1e-15 }
tirefe.check{ name = "node spacings the tire turned between the passages", value = summary.node_spacings_between,
              expected = 100 * 0.85 / 0.27, relative = 1e-12 }
tirefe.check{ name = "written to the results", value = results.node_spacings_between_passages,
              expected = summary.node_spacings_between, tolerance = 0 }
local one = require("cleat_summary").report{ model = model, rig = rig, passages = passages, record = record,
  ring_time = 0.15, end_time = 3.2, speed_kmh = 51.3, tread = contact, unloaded_radius = 0.2715, deflection = 0.025 }
tirefe.check{ name = "one passage rung out by 3.2 s: no passage before", value = one.before == nil and 1 or 0,
              expected = 1, tolerance = 0 }
tirefe.check{ name = "impacts a turn apart [s]", value = summary.impact_period, expected = rig:turn_time(),
              tolerance = 2.5e-4 }
tirefe.check{ name = "a turn = pi D / v [s]", value = rig:turn_time(), expected = math.pi * 1.7 / (51.3 / 3.6),
              relative = 1e-15 }
tirefe.check{ name = "rolling radius = speed / spin [m]", value = summary.rolling_radius, expected = 0.27,
              relative = 1e-12 }
tirefe.check{ name = "belt radius: the 100-gon's perimeter / 2 pi [m]", value = summary.belt_radius,
              expected = 0.27 * 100 * math.sin(math.pi / 100) / math.pi, relative = 1e-12 }
local no_passage = require("cleat_summary").report{ model = model, rig = rig, passages = passages, record = record,
  ring_time = 0.15, end_time = 2.9, speed_kmh = 51.3, tread = contact, unloaded_radius = 0.2715, deflection = 0.025 }
tirefe.check{ name = "none rung out by 2.9 s: an empty summary", value = next(no_passage) == nil and 1 or 0,
              expected = 1, tolerance = 0 }
local cleat = { cleat_angle = -math.pi / 2, cleat_length = 0.66, end_time = 2.9 }
local ok, message = pcall(rig.require_full_speed_passage, rig, cleat, 0.15)
local refused = not ok and message:find("give end_time >= 2.985 s", 1, true)
tirefe.check{ name = "a run too short is refused, naming the end_time needed", value = refused and 1 or 0,
              expected = 1, tolerance = 0 }
cleat.end_time = 3.0
tirefe.check{ name = "a run long enough is taken",
              value = pcall(rig.require_full_speed_passage, rig, cleat, 0.15) and 1 or 0, expected = 1, tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 24);
}

TEST_CASE("lua/guard.lua refuses a parameter out of its range, by name", "[lua][modules]") {
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("guard_deck.lua", R"(
local guard = require("guard")
local p = { load = 3800, dt = 0, height = 0, depth = -0.01, nan = 0 / 0 }
local function refusal(check, names)
  local ok, message = pcall(check, p, names)
  return ok and "" or message
end
tirefe.check{ name = "positive: 3800 passes", value = #refusal(guard.positive, { "load" }), expected = 0, tolerance = 0 }
tirefe.check{ name = "positive: 0 is refused by name", value = refusal(guard.positive, { "load", "dt" })
              == "parameter dt = 0 must be positive" and 1 or 0, expected = 1, tolerance = 0 }
tirefe.check{ name = "positive: NaN is refused", value = #refusal(guard.positive, { "nan" }) > 0 and 1 or 0,
              expected = 1, tolerance = 0 }
tirefe.check{ name = "non-negative: 0 passes", value = #refusal(guard.non_negative, { "height" }), expected = 0,
              tolerance = 0 }
tirefe.check{ name = "non-negative: -0.01 is refused by name", value = refusal(guard.non_negative, { "depth" })
              == "parameter depth = -0.01 must not be negative" and 1 or 0, expected = 1, tolerance = 0 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 5);
}

TEST_CASE("TireOnRoad and lua/tire_on_road.lua put the road under the tire's lowest tread node",
          "[lua][modules][vehicle]") {
  // Both the C++ tire and the deck module find the road level from the inflated tread
  // nodes, and the C++ tire puts its tread contact on the chords between them.
  const tirefe::TireParameters layered = tirefe::macros::load_tire_parameters("tires.145SR12_tread_layer");
  tirefe::TireOnRoad tire(
      layered, [](double level) { return std::make_shared<tirefe::FlatRoad>(Eigen::Vector2d(0.0, level)); },
      tirefe::RoadContact{});
  const std::vector<int>& tread = tire.tire().tread_nodes;
  REQUIRE(tire.contact().size() == 100);
  for (int e = 0; e < tire.contact().size(); ++e)
    CHECK(tire.contact().element_nodes(e) == std::vector<int>{tread[e], tread[(e + 1) % 100]});
  const double r_outer = 0.543 / 2;
  CHECK(tire.road_level() == Approx(-r_outer).margin(0.001));  // the tread, inflated

  std::ostringstream expected;
  expected.precision(17);
  expected << tire.road_level();
  tirefe::testing::TempDir folder;
  const std::string deck = folder.write("level_deck.lua", R"(
local model = tirefe.model{ title = "level" }
local tire, level = require("tire_on_road").inflated(model, require("tires.145SR12_tread_layer"))
tirefe.check{ name = "the deck module's road level = TireOnRoad's [m]", value = level, expected = )" +
                                                              expected.str() + R"(, tolerance = 1e-7 }
)");
  tirefe::testing::check_deck_passes(deck, folder.path("out"), 1);
}
