// The vehicle macros: the spindle force of a tire driven from the deck (docs/spindle.md)
// and a vehicle on the deck's tire models (docs/vehicle.md).
//
// A model's driven spindles are kept per node in its DeckModel, so they die with the model.
#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <memory>
#include <stdexcept>

#include "deck/deck_model.hpp"
#include "macros/macro_table.hpp"
#include "vehicle/tire_group.hpp"
#include "vehicle/tire_spindle.hpp"
#include "vehicle/vehicle.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

void push_row(lua_State* L, const double* values) {
  lua_createtable(L, 3, 0);
  for (int j = 0; j < 3; ++j) {
    lua_pushnumber(L, values[j]);
    lua_rawseti(L, -2, j + 1);
  }
}

int spindle_force_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const int node = deck_node(deck, arguments.integer("node"));
  const SpinMode spin = arguments.has("spin") ? SpinMode::Driven : SpinMode::Free;
  TireSpindle* spindle = deck.driven_spindle(node);
  if (!spindle) {
    spindle = &deck.drive_spindle(node, spin);
  } else if (spindle->spin() != spin) {
    throw ModelError(std::string("this spindle was first driven with ") +
                     (spindle->spin() == SpinMode::Free ? "a free spin: leave out 'spin'" : "its spin: give 'spin'"));
  }
  deck.output_or_default();  // accepted steps are written like any other
  SpindleInput input;
  input.time_step = arguments.number("dt");
  input.x = arguments.number("x");
  input.y = arguments.number("y");
  input.spin = spin == SpinMode::Driven ? arguments.number("spin") : 0.0;
  const SpindleReply reply = spindle->solve_step(input);
  if (arguments.boolean("commit")) spindle->commit();

  lua_createtable(L, 0, 7);
  const char* names[] = {"fx", "fy", "mz"};
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, reply.force[i]);
    lua_setfield(L, -2, names[i]);
  }
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    push_row(L, reply.jacobian[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "jacobian");
  lua_pushnumber(L, reply.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, reply.newton_iterations);
  lua_setfield(L, -2, "newton_iterations");
  return 1;
}

struct VehicleView {
  const Vehicle* vehicle = nullptr;  // during tirefe.vehicle{...} only; NaN afterwards
};

Suspension suspension_of(const MacroArguments& corner) {
  Suspension s;
  auto curve = [&](const char* table_key, const char* slope_key, double offset) {
    if (corner.has(table_key) == corner.has(slope_key))
      throw ModelError(std::string("give either '") + table_key + "' or '" + slope_key + "'");
    if (corner.has(slope_key)) {
      const double slope = corner.number(slope_key);
      return ForceCurve({{0.0, offset}, {1.0, offset + slope}});
    }
    std::vector<std::pair<double, double>> points;
    for (const auto& row : corner.number_matrix(table_key)) {
      if (row.size() != 2) throw ModelError(std::string("each '") + table_key + "' point is {argument, force}");
      points.emplace_back(row[0], row[1]);
    }
    try {
      return ForceCurve(std::move(points));
    } catch (const std::invalid_argument& problem) {
      throw ModelError(std::string("'") + table_key + "': " + problem.what());
    }
  };
  s.spring = curve("spring", "spring_rate", corner.number("preload"));
  s.damper = curve("damper", "damping", 0.0);
  s.bumper_gap = corner.number("bumper_gap");
  s.bumper_stiffness = corner.number("bumper_stiffness");
  s.fore_aft_stiffness = corner.number("fore_aft_stiffness");
  s.fore_aft_damping = corner.number("fore_aft_damping");
  return s;
}

const MacroSpec& corner_spec();
const MacroSpec& body_spec();

void push_list(lua_State* L, const std::vector<double>& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

/// The tires of 'decks' behind one exchange: the session's (an MPI run's) or threads here.
std::unique_ptr<TireExchange> tire_exchange(DeckSession& session, std::vector<TireSpindle*> spindles,
                                            const std::vector<DeckModel*>& decks, bool threads) {
  if (!session.tire_exchange) return std::make_unique<TireGroup>(std::move(spindles), threads);
  std::vector<int> owners;
  for (const DeckModel* deck : decks) owners.push_back(session.processes.owner(deck->index()));
  return session.tire_exchange(std::move(spindles), std::move(owners), threads);
}

/// After a vehicle run (or its failure) the models another process solved are stale here.
struct RemoteTiresGuard {
  const std::vector<DeckModel*>& decks;
  ~RemoteTiresGuard() {
    for (DeckModel* deck : decks)
      if (!deck->owned()) deck->mark_advanced_elsewhere("tirefe.vehicle");
  }
};

std::vector<Vehicle::StepWindow> step_windows_of(const MacroArguments& arguments) {
  std::vector<Vehicle::StepWindow> windows;
  if (!arguments.has("step_windows")) return windows;
  for (const auto& row : arguments.number_matrix("step_windows")) {
    if (row.size() != 3 || !(row[1] > row[0]) || !(row[2] > 0.0))
      throw ModelError("each 'step_windows' window is {from [s], to [s], dt [s]} with from < to and dt > 0");
    windows.push_back({row[0], row[1], row[2]});
  }
  return windows;
}

/// The corners of tirefe.vehicle{...} with the deck model, tire heading and free-spinning
/// spindle of each corner's tire.
struct VehicleCorners {
  std::vector<Corner> corners;
  std::vector<Heading> headings;  // of each corner's tire: the wheel axes of its returned forces
  std::vector<DeckModel*> decks;
  std::vector<TireSpindle*> spindles;
};

Body body_of(lua_State* L, const MacroArguments& arguments) {
  arguments.push_value("body");
  const MacroArguments body_arguments(L, lua_gettop(L), body_spec());
  return Body{body_arguments.number("mass"), body_arguments.number("pitch_inertia"),
              body_arguments.number("roll_inertia")};
}

/// Reads one corner (its table on the top of the stack) into 'read'.
void read_corner(lua_State* L, int i, VehicleCorners& read) {
  const MacroArguments corner_arguments(L, lua_gettop(L), corner_spec());
  corner_arguments.push_value("model");
  DeckModel& deck = check_model(L, lua_gettop(L));
  lua_pop(L, 1);
  Corner corner;
  corner.name = corner_arguments.string_or("name", "corner" + std::to_string(i));
  corner.x = corner_arguments.number("x");
  corner.y = corner_arguments.number("y");
  corner.mass = corner_arguments.number("mass");
  corner.suspension = suspension_of(corner_arguments);
  const int node = deck_node(deck, corner_arguments.integer("spindle"));
  read.headings.push_back(deck.wheel_heading(node));
  TireSpindle* spindle = deck.driven_spindle(node);
  if (!spindle) spindle = &deck.drive_spindle(node, SpinMode::Free);
  if (spindle->spin() != SpinMode::Free)
    throw ModelError("corner '" + corner.name + "': the spindle spin must be free");
  read.corners.push_back(corner);
  read.decks.push_back(&deck);
  read.spindles.push_back(spindle);
}

VehicleCorners corners_of(lua_State* L, const MacroArguments& arguments) {
  VehicleCorners read;
  arguments.push_value("corners");
  const int list = lua_gettop(L);
  const int count = static_cast<int>(luaL_len(L, list));
  if (count < 1) throw ModelError("'corners' lists at least one corner");
  for (int i = 1; i <= count; ++i) {
    lua_rawgeti(L, list, i);
    if (!lua_istable(L, -1)) throw ModelError("corner " + std::to_string(i) + " must be a table");
    read_corner(L, i, read);
    lua_pop(L, 1);
  }
  return read;
}

/// The vehicle integrates as its tires do, with their scheme.
VehicleSettings settings_of(const MacroArguments& arguments, const std::vector<DeckModel*>& decks) {
  const bool threads = arguments.boolean("threads");
  for (DeckModel* deck : decks)
    if (threads && deck->calls_lua())
      throw ModelError("a tire model calls a Lua load function ('fn'): solve it with threads = false");
  const Integrator& scheme = decks[0]->analysis().integrator();
  for (DeckModel* deck : decks)
    if (!deck->analysis().integrator().same_scheme(scheme))
      throw ModelError("every corner's tire needs the same integrator (model:integrator{...})");
  // A quasi-static tire is refused where it is driven (it has no rates).
  VehicleSettings settings;
  // The body keeps the default predictor (its motion is smooth), whatever the tires start from.
  if (scheme.is_dynamic()) settings.scheme = scheme.with_predictor(Integrator::Predictor::SameAcceleration);
  settings.gravity = arguments.number("gravity");
  settings.residual_tolerance = arguments.number("tolerance");
  settings.jacobian = arguments.string("jacobian") == "direct" ? SpindleJacobianSource::Direct
                                                               : SpindleJacobianSource::FiniteDifference;
  return settings;
}

/// History channels of the vehicle in every corner's result file; NaN once the run is over.
void add_vehicle_channels(const std::vector<DeckModel*>& decks, const Vehicle& vehicle,
                          const std::shared_ptr<VehicleView>& view) {
  for (size_t i = 0; i < decks.size(); ++i) {
    io::ResultFile& file = decks[i]->output_or_default();
    const int c = static_cast<int>(i);
    auto channel = [view](std::function<double(const Vehicle&)> read) {
      return [view, read](const State&, const StepRecord&) {
        return view->vehicle ? read(*view->vehicle) : std::numeric_limits<double>::quiet_NaN();
      };
    };
    file.add_channel("vehicle_heave", "m", channel([](const Vehicle& v) { return v.state().displacement[0]; }));
    if (vehicle.body_dofs() == 3) {
      file.add_channel("vehicle_pitch", "rad", channel([](const Vehicle& v) { return v.state().displacement[1]; }));
      file.add_channel("vehicle_roll", "rad", channel([](const Vehicle& v) { return v.state().displacement[2]; }));
    }
    file.add_channel("jounce", "m", channel([c](const Vehicle& v) { return v.jounce(c); }));
    file.add_channel("wheel_z", "m",
                     channel([c](const Vehicle& v) { return v.state().displacement[v.wheel_vertical_dof(c)]; }));
    file.add_channel("wheel_x", "m",
                     channel([c](const Vehicle& v) { return v.state().displacement[v.wheel_fore_aft_dof(c)]; }));
  }
}

/// The series tirefe.vehicle{...} returns, one entry every 'history_every' steps.
struct VehicleSeries {
  explicit VehicleSeries(size_t corners) : jounce(corners), wheel_z(corners), fx(corners), fz(corners) {}
  std::vector<double> time, heave, pitch, roll;
  std::vector<std::vector<double>> jounce, wheel_z, fx, fz;  // per corner

  void record(const Vehicle& v, const std::vector<Heading>& headings) {
    time.push_back(v.time());
    heave.push_back(v.state().displacement[0]);
    pitch.push_back(v.body_dofs() == 3 ? v.state().displacement[1] : 0.0);
    roll.push_back(v.body_dofs() == 3 ? v.state().displacement[2] : 0.0);
    for (size_t i = 0; i < jounce.size(); ++i) {
      const int c = static_cast<int>(i);
      jounce[i].push_back(v.jounce(c));
      wheel_z[i].push_back(v.state().displacement[v.wheel_vertical_dof(c)]);
      // The committed spindle force is the carrier's force on the tire: the spindle's reaction.
      const Eigen::Vector3d load = wheel_load_from_reaction(v.spindle_force(c), headings[i]);
      fx[i].push_back(load.x());
      fz[i].push_back(load.y());
    }
  }
};

/// Steps the vehicle with its tires kept busy; returns the wall time [s].
double run_vehicle(Vehicle& vehicle, const std::vector<DeckModel*>& decks, const MacroArguments& arguments,
                   const std::vector<Vehicle::StepWindow>& windows, VehicleView& view) {
  const auto start = std::chrono::steady_clock::now();
  const RemoteTiresGuard remote_tires{decks};
  std::vector<std::unique_ptr<DeckModel::Busy>> busy;  // a tire's load function must not step or change a tire
  for (DeckModel* deck : decks)
    if (deck->busy_with().empty()) busy.push_back(std::make_unique<DeckModel::Busy>(*deck, "tirefe.vehicle"));
  try {
    vehicle.advance(arguments.number("duration"), arguments.number("dt"), windows);
  } catch (...) {
    view.vehicle = nullptr;
    throw;
  }
  view.vehicle = nullptr;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Pushes tirefe.vehicle's returned table: totals, series, and per corner series.
void push_vehicle_results(lua_State* L, const VehicleStatistics& s, double wall, const VehicleSeries& series) {
  lua_createtable(L, 0, 16);
  const std::pair<const char*, double> totals[] = {
      {"steps", s.steps},
      {"corrector_iterations", s.corrector_iterations},
      {"tire_solves", s.tire_solves},
      {"tire_newton_iterations", static_cast<double>(s.tire_newton_iterations)},
      {"cuts", s.cuts},
      {"backtracks", s.backtracks},
      {"wall_time", wall}};
  for (const auto& [name, value] : totals) {
    lua_pushnumber(L, value);
    lua_setfield(L, -2, name);
  }
  const std::pair<const char*, const std::vector<double>*> body_series[] = {
      {"time", &series.time}, {"heave", &series.heave}, {"pitch", &series.pitch}, {"roll", &series.roll}};
  for (const auto& [name, values] : body_series) {
    push_list(L, *values);
    lua_setfield(L, -2, name);
  }
  lua_createtable(L, static_cast<int>(series.jounce.size()), 0);
  for (size_t i = 0; i < series.jounce.size(); ++i) {
    lua_createtable(L, 0, 4);
    const std::pair<const char*, const std::vector<double>*> corner_series[] = {
        {"jounce", &series.jounce[i]}, {"wheel_z", &series.wheel_z[i]}, {"fx", &series.fx[i]}, {"fz", &series.fz[i]}};
    for (const auto& [name, values] : corner_series) {
      push_list(L, *values);
      lua_setfield(L, -2, name);
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "corners");
}

int vehicle_macro(lua_State* L, DeckSession& session, const MacroArguments& arguments) {
  const std::vector<Vehicle::StepWindow> windows = step_windows_of(arguments);
  const Body body = body_of(L, arguments);
  const VehicleCorners read = corners_of(L, arguments);
  const VehicleSettings settings = settings_of(arguments, read.decks);
  const std::unique_ptr<TireExchange> tires =
      tire_exchange(session, read.spindles, read.decks, arguments.boolean("threads"));
  Vehicle vehicle(body, read.corners, *tires, settings);

  auto view = std::make_shared<VehicleView>();
  view->vehicle = &vehicle;
  add_vehicle_channels(read.decks, vehicle, view);
  const int every = static_cast<int>(arguments.integer("history_every"));
  VehicleSeries series(read.corners.size());
  vehicle.add_step_observer([&](const Vehicle& v) {
    if (v.statistics().steps % every == 0) series.record(v, read.headings);
  });
  const double wall = run_vehicle(vehicle, read.decks, arguments, windows, *view);
  push_vehicle_results(L, vehicle.statistics(), wall, series);
  return 1;
}

ParameterSpec non_negative(const char* key, const char* unit, const char* doc) {
  return {key, VT::Number, false, unit, doc, std::string("0"), Range::NonNegative};
}

const MacroSpec& body_spec() {
  static const MacroSpec spec{
      "vehicle body",
      "",
      {{"mass", VT::Number, true, "kg", "sprung mass", std::nullopt, Range::Positive},
       non_negative("pitch_inertia", "kg m^2", "about the lateral axis (needed with several corners)"),
       non_negative("roll_inertia", "kg m^2", "about the longitudinal axis (needed with several corners)")},
      ""};
  return spec;
}

const MacroSpec& corner_spec() {
  static const MacroSpec spec{
      "vehicle corner",
      "",
      {{"name", VT::String, false, "", "corner name", std::string("corner<i>")},
       {"model", VT::Any, true, "", "the tire's model (tirefe.model{...}, dynamic, tire pressed on its road)"},
       {"spindle", VT::Integer, true, "", "the tire's spindle node (tire.spindle)", std::nullopt, Range::Positive},
       {"x", VT::Number, false, "m", "attachment forward of the body's centre of mass", std::string("0")},
       {"y", VT::Number, false, "m", "attachment left of the body's centre of mass", std::string("0")},
       {"mass", VT::Number, true, "kg", "wheel carrier without the tire", std::nullopt, Range::Positive},
       {"spring", VT::NumberMatrix, false, "m, N", "spring force on the body vs jounce {{d, F}, ...}"},
       {"spring_rate", VT::Number, false, "N/m", "linear spring instead of a table", std::nullopt, Range::NonNegative},
       {"preload", VT::Number, false, "N", "spring force at zero jounce (with spring_rate)", std::string("0")},
       {"damper", VT::NumberMatrix, false, "m/s, N", "damper force on the body vs jounce rate {{v, F}, ...}"},
       {"damping", VT::Number, false, "N s/m", "linear damper instead of a table", std::nullopt, Range::NonNegative},
       non_negative("bumper_gap", "m", "jounce where the bumper starts"),
       non_negative("bumper_stiffness", "N/m^2", "bumper force k (d - gap)^2"),
       non_negative("fore_aft_stiffness", "N/m", "carrier to body along x"),
       non_negative("fore_aft_damping", "N s/m", "carrier to body along x")},
      ""};
  return spec;
}

}  // namespace

void add_vehicle_macros(MacroTable& table) {
  table.model_macros.push_back(
      {{"spindle_force",
        "Solves one dynamic step of the tire with its spindle held at {x, y} (and turned to 'spin', or spinning "
        "freely without it) at the end of the step, and returns the force that holds it there and its Jacobian "
        "(docs/model.md section 6): {fx, fy, mz, jacobian = 3x3 d(fx, fy, mz)/d(x, y, spin), time, "
        "newton_iterations}. The step stays a trial (calling again re-solves it from the same state) until "
        "'commit' accepts it. The model's integrator must be dynamic; docs/spindle.md.",
        {{"node", VT::Integer, true, "", "the tire's spindle node (tire.spindle)", std::nullopt, Range::Positive},
         {"x", VT::Number, true, "m", "spindle centre x at the end of the step (absolute)"},
         {"y", VT::Number, true, "m", "spindle centre y at the end of the step (absolute)"},
         {"spin", VT::Number, false, "rad", "spindle rotation from the reference, counter-clockwise (none: free spin)"},
         {"dt", VT::Number, true, "s", "time step from the committed time", std::nullopt, Range::Positive},
         {"commit", VT::Boolean, false, "", "accept the step after solving it", std::string("false")}},
        "local s = model:spindle_force{ node = tire.spindle, x = 0, y = -0.02, dt = 1e-3, commit = true }"},
       spindle_force_macro});
  table.module_macros.push_back(
      {{"vehicle",
        "Runs a vehicle on FE tires for 'duration' (docs/vehicle.md): a body (heave; with several corners also "
        "pitch and roll) and corners, each a wheel carrier on a suspension (spring table or rate, damper table or "
        "rate, jounce bumper, fore-aft bushing) riding on the tire of its own model (tirefe.model{...} with "
        "model:tire, a road and contact, pressed and made dynamic; its spindle then spins freely). The vehicle "
        "integrates like its tires (their generalized-alpha scheme), each corrector iteration asking every tire for its spindle "
        "force and Jacobian, the tires in concurrent threads. Every corner's result file gets the channels "
        "vehicle_heave (and _pitch, _roll), jounce, wheel_z, wheel_x. Returns {steps, corrector_iterations, "
        "tire_solves, tire_newton_iterations, cuts, backtracks, wall_time, time, heave, pitch, roll, "
        "corners = {{jounce, wheel_z, fx, fz}, ...}} (fx, fz: the force the tire exerts on the wheel in its ISO 8855 "
        "wheel axes, docs/output.md).",
        {{"body", VT::Table, true, "", "{mass [kg], pitch_inertia [kg m^2], roll_inertia [kg m^2]}"},
         {"corners", VT::Table, true, "",
          "list of {name, model, spindle, x, y, mass, spring | spring_rate + preload, damper | damping, "
          "bumper_gap, bumper_stiffness, fore_aft_stiffness, fore_aft_damping} (docs/vehicle.md)"},
         {"duration", VT::Number, true, "s", "simulated time", std::nullopt, Range::Positive},
         {"dt", VT::Number, true, "s", "vehicle (and tire) time step", std::nullopt, Range::Positive},
         {"step_windows", VT::NumberMatrix, false, "s",
          "windows {{from, to, dt}, ...} of absolute time stepped with their own dt (finer at an obstacle, coarser where nothing happens)"},
         {"gravity", VT::Number, false, "m/s^2", "acting on the body and the carriers", std::string("9.81"),
          Range::NonNegative},
         {"tolerance", VT::Number, false, "", "corrector: |r|_inf / total weight", std::string("1e-8"),
          Range::Positive},
         {"jacobian",
          VT::String,
          false,
          "",
          "spindle Jacobian of the corrector",
          std::string("direct"),
          Range::Any,
          {"direct", "difference"}},
         {"threads", VT::Boolean, false, "", "solve the tires concurrently", std::string("true")},
         {"history_every", VT::Integer, false, "", "steps between entries of the returned series", std::string("1"),
          Range::Positive}},
        "local run = tirefe.vehicle{ body = { mass = 400 }, corners = { { model = tm, spindle = tire.spindle, "
        "mass = 35, spring_rate = 2e4, preload = 3900, damping = 1500 } }, duration = 1.0, dt = 1e-3 }"},
       vehicle_macro});
}

}  // namespace tirefe::macros
