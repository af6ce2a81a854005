// The C API of include/tirefe.h over TireOnRoad and TireSpindle (docs/coupling.md).
// Every entry point catches whatever the C++ side throws and turns it into a status and
// a message kept in the handle: nothing unwinds into the C caller. The handles a host
// holds are numbers looked up in a table of open tires and saved states, never addresses
// dereferenced here: a closed, freed or made-up handle is an error, not a crash.
#include "tirefe.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <new>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "formats/road_file.hpp"
#include "deck/checkpoint.hpp"
#include "deck/deck_model.hpp"
#include "deck/interrupt.hpp"
#include "deck/lua_module_dir.hpp"
#include "macros/macro_table.hpp"
#include "tire/wheel_axes.hpp"
#include "tirefe/version.hpp"
#include "vehicle/tire_on_road.hpp"

/// A deck's Lua state and session, which own the model of a tire opened from a deck.
struct DeckHold {
  tirefe::macros::DeckSession session;
  std::unique_ptr<tirefe::macros::LuaSandbox> sandbox;
};

/// A host's step budget (tirefe_set_step_budget) and what it saw: the wall time, the
/// iterations and the Newton ending of the pending step, added to the report when the step
/// is committed.
class BudgetWatch {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr double kDefaultResidual = 1e-4;

  /// Sets the budget on the analysis's Newton; a budget starts every step from the zero-
  /// acceleration predictor (docs/dynamics.md), no budget from the analysis's own again.
  void set(const tirefe_step_budget& budget, tirefe::Analysis& analysis) {
    using tirefe::Predictor;
    if (!own_predictor_) own_predictor_ = analysis.integrator().predictor();
    const bool budgeted = budget.max_iterations > 0 || budget.max_time > 0.0;
    const Predictor predictor = budgeted ? Predictor::ZeroAcceleration : *own_predictor_;
    if (analysis.integrator().predictor() != predictor)
      analysis.set_integrator(analysis.integrator().with_predictor(predictor));
    tirefe::NewtonSettings& newton = analysis.newton_settings();
    budget_ = budget;
    newton.budget_iterations = budget.max_iterations;
    newton.budget_time = budget.max_time;
    newton.budget_residual = budget.max_residual > 0.0 ? budget.max_residual : kDefaultResidual;
    report_ = tirefe_budget_report{};
    forget();
  }
  /// A solve of the pending step took 'seconds'; 'newton' is its report when it succeeded.
  void solved(double seconds, const tirefe::NewtonReport* newton) {
    pending_time_ += seconds;
    pending_converged_ = !newton || newton->converged;
    pending_residual_ = newton ? newton->relative_residual : 0.0;
    pending_iterations_ = newton ? newton->iterations : 0;
  }
  /// The pending step was committed, its commit taking 'seconds'.
  void committed(double seconds) {
    const double step_time = pending_time_ + seconds;
    ++report_.steps;
    if (!pending_converged_) {
      ++report_.unconverged;
      report_.worst_residual = std::max(report_.worst_residual, pending_residual_);
    }
    if (budget_.max_iterations > 0 && pending_iterations_ > budget_.max_iterations) ++report_.overruns;
    if (budget_.max_time > 0.0 && step_time > budget_.max_time) ++report_.time_misses;
    report_.worst_time = std::max(report_.worst_time, step_time);
    forget();
  }
  /// The pending step was reverted.
  void forget() {
    pending_time_ = 0.0;
    pending_converged_ = true;
    pending_iterations_ = 0;
  }
  const tirefe_budget_report& report() const { return report_; }
  static double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

 private:
  tirefe_step_budget budget_{0, 0.0, 0.0};
  tirefe_budget_report report_{};
  std::optional<tirefe::Predictor> own_predictor_;  // the analysis's before any budget
  double pending_time_ = 0.0;                       // [s] of the pending step's solves
  bool pending_converged_ = true;
  double pending_residual_ = 0.0;
  int pending_iterations_ = 0;
};

/// An open tire, behind its tirefe_tire* handle.
struct OpenTire {
  std::mutex mutex;  // one caller at a time per tire
  // Opened from parameters: the tire on its flat road; from a deck: the deck and a spindle
  // of its model (destroyed before the deck).
  std::unique_ptr<tirefe::TireOnRoad> tire;
  std::unique_ptr<DeckHold> deck;
  std::unique_ptr<tirefe::TireSpindle> deck_spindle;
  tirefe::Analysis* analysis = nullptr;
  int spindle_node = -1;
  tirefe::TireSpindle* spindle = nullptr;
  tirefe::Heading heading = tirefe::Heading::PlusX;  // of the wheel axes every value crosses the API in
  bool has_trial = false;                            // a solved step waits for commit or revert
  BudgetWatch budget;
  std::string message;
};

/// A saved state, behind its tirefe_saved_state* handle.
struct SavedState {
  tirefe::macros::Checkpoint checkpoint;
};

namespace {

using namespace tirefe;
using macros::ParameterValue;

/// The status of an exception thrown by the C++ side, its text in 'message'.
tirefe_status status_of_current_exception(std::string& message) {
  try {
    throw;
  } catch (const StepFailure& failure) {
    message = failure.what();
    return TIREFE_STEP_FAILED;
  } catch (const ModelError& error) {
    message = error.what();
    return TIREFE_MODEL_ERROR;
  } catch (const std::bad_alloc&) {
    message = "out of memory";
    return TIREFE_OUT_OF_MEMORY;
  } catch (const std::exception& error) {
    message = error.what();
    return TIREFE_INTERNAL_ERROR;
  } catch (...) {
    message = "unknown failure";
    return TIREFE_INTERNAL_ERROR;
  }
}

/// Held by every call on a tire opened from a deck: such tires write result files, and
/// the HDF5 library is not thread-safe.
std::mutex deck_tires_mutex;

/// The next handle's number, one count for every kind: a tire's handle is no state's.
std::uintptr_t next_handle_number() {
  static std::atomic<std::uintptr_t> next{0x7e1fe0000000};  // far from where heaps and stacks lie
  return next += 16;
}

/// The open objects of one kind by their handles. A handle is a number (never reused, never
/// zero) in the guise of a pointer: looking it up reads no memory of the host's, so NULL,
/// a closed or freed handle and any other pointer are told apart from an open one.
template <class Object, class Handle>
class HandleTable {
 public:
  Handle* add(std::shared_ptr<Object> object) {
    const std::uintptr_t number = next_handle_number();
    const std::lock_guard<std::mutex> lock(mutex_);
    open_.emplace(number, std::move(object));
    return reinterpret_cast<Handle*>(number);
  }
  /// The object of 'handle', or null; the object lives while the caller holds it.
  std::shared_ptr<Object> find(const Handle* handle) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = open_.find(reinterpret_cast<std::uintptr_t>(handle));
    return found == open_.end() ? nullptr : found->second;
  }
  /// Takes 'handle' out of the table (it is closed); null if it was not open.
  std::shared_ptr<Object> remove(const Handle* handle) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = open_.find(reinterpret_cast<std::uintptr_t>(handle));
    if (found == open_.end()) return nullptr;
    std::shared_ptr<Object> object = std::move(found->second);
    open_.erase(found);
    return object;
  }

 private:
  mutable std::mutex mutex_;
  std::unordered_map<std::uintptr_t, std::shared_ptr<Object>> open_;
};

HandleTable<OpenTire, tirefe_tire>& open_tires() {
  static HandleTable<OpenTire, tirefe_tire> table;
  return table;
}
HandleTable<SavedState, tirefe_saved_state>& saved_states() {
  static HandleTable<SavedState, tirefe_saved_state> table;
  return table;
}

/// A tire opened from a deck closes its result file when it is freed: under the lock of
/// the deck tires, in whichever thread lets go of it last.
void delete_tire(OpenTire* tire) {
  std::unique_lock<std::mutex> deck_lock(deck_tires_mutex, std::defer_lock);
  if (tire->deck) deck_lock.lock();
  delete tire;
}

constexpr const char* kNotATire = "not an open tire (NULL, closed, or not made by tirefe_open or tirefe_open_deck)";

/// The end of a call that tirefe_cancel may stop: the cancel is answered (a later call is
/// not stopped by it), and the call's failure, if it stopped, is TIREFE_CANCELLED.
tirefe_status answer_cancel(tirefe_status status) {
  int cancel = macros::kHostCancel;
  const bool cancelled = macros::stop_signal().compare_exchange_strong(cancel, 0);
  return cancelled && status != TIREFE_OK ? TIREFE_CANCELLED : status;
}

/// Runs 'body' on a deck's tire inside a protected call of the deck's Lua state, as the
/// deck runs its macros: a Lua error of the deck's code that the body calls back (a load
/// function's error, the stop of tirefe_cancel) unwinds to here, a deck error. Outside a
/// protected call Lua would leave the state with its hooks off after an error in a hook.
template <class Body>
tirefe_status in_deck_lua(OpenTire& tire, Body& body) {
  struct Call {
    Body& body;
    OpenTire& tire;
    tirefe_status status = TIREFE_OK;
    std::exception_ptr failure;
  } call{body, tire, TIREFE_OK, nullptr};
  lua_State* L = tire.deck->sandbox->state();
  lua_pushcfunction(L, [](lua_State* state) -> int {
    Call& call = *static_cast<Call*>(lua_touserdata(state, 1));
    try {
      call.status = call.body(call.tire);
    } catch (const std::exception&) {  // Lua's own errors (a pointer type) go on to lua_pcall
      call.failure = std::current_exception();
    }
    return 0;
  });
  lua_pushlightuserdata(L, &call);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
    const std::string message = macros::error_text(L, -1);
    lua_pop(L, 1);
    throw ModelError(message);
  }
  if (call.failure) std::rethrow_exception(call.failure);
  return call.status;
}

/// Runs 'body' on the locked tire; every exception becomes a status and the message.
template <class Body>
tirefe_status guarded(tirefe_tire* handle, Body&& body) {
  const std::shared_ptr<OpenTire> tire = open_tires().find(handle);  // released last, after the locks
  if (!tire) return TIREFE_INVALID_ARGUMENT;
  std::unique_lock<std::mutex> deck_lock(deck_tires_mutex, std::defer_lock);
  if (tire->deck) deck_lock.lock();
  std::lock_guard<std::mutex> lock(tire->mutex);
  tire->message.clear();
  tirefe_status status;
  try {
    status = tire->deck ? in_deck_lua(*tire, body) : body(*tire);
  } catch (...) {
    status = status_of_current_exception(tire->message);
  }
  // A deck's Lua (its load functions) runs in a deck tire's steps: tirefe_cancel stops it.
  return tire->deck ? answer_cancel(status) : status;
}

tirefe_status refuse(OpenTire& tire, tirefe_status status, std::string message) {
  tire.message = std::move(message);
  return status;
}

void copy_message(const std::string& message, char* error, size_t error_size) {
  if (error && error_size > 0) std::snprintf(error, error_size, "%s", message.c_str());
}

/// Runs 'body' for a call without a tire handle: every exception becomes a status and
/// the message in 'error'.
template <class Body>
tirefe_status without_handle(char* error, size_t error_size, Body&& body) {
  std::string message;
  try {
    body();
  } catch (const std::invalid_argument& invalid) {
    copy_message(invalid.what(), error, error_size);
    return TIREFE_INVALID_ARGUMENT;
  } catch (...) {
    const tirefe_status status = status_of_current_exception(message);
    copy_message(message, error, error_size);
    return status;
  }
  copy_message("", error, error_size);
  return TIREFE_OK;
}

std::vector<ParameterValue> parameter_values(const tirefe_parameter* overrides, size_t count) {
  std::vector<ParameterValue> values;
  for (size_t i = 0; i < count; ++i) {
    if (!overrides[i].name) throw std::invalid_argument("override " + std::to_string(i) + " has no name");
    if (!std::isfinite(overrides[i].value))
      throw std::invalid_argument(std::string("override '") + overrides[i].name + "' is not a finite number");
    for (const ParameterValue& earlier : values)
      if (earlier.first == overrides[i].name)
        throw std::invalid_argument(std::string("override '") + overrides[i].name + "' is given twice");
    values.emplace_back(overrides[i].name, overrides[i].value);
  }
  return values;
}

TireOnRoad::RoadMaker flat_road() {
  return [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); };
}

/// The road of options.road in the tire's plane: the file's x along the heading from
/// road_start, its height 0 at 'level' (where the inflated tire touches).
std::shared_ptr<const RigidSurface> file_road(const tirefe_options& options, double level) {
  const std::string file = options.road;
  std::optional<RoadTrack> track;
  if (options.road_track) {
    const std::string name = options.road_track;
    if (name != "left" && name != "right")
      throw std::invalid_argument("options.road_track must be \"left\", \"right\" or NULL, not \"" + name + "\"");
    track = name == "left" ? RoadTrack::Left : RoadTrack::Right;
  }
  const auto ends_with = [&file](const char* extension) {
    const std::string tail = file.size() >= 4 ? file.substr(file.size() - 4) : "";
    std::string lower = tail;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower == extension;
  };
  const bool crg = ends_with(".crg");
  if (crg && track)
    throw std::invalid_argument(
        "options.road_track picks a track of a .rdf or .csv file; the track of the OpenCRG "
        "road '" +
        file + "' is chosen by options.road_lateral");
  if (!crg && options.road_lateral != 0.0)
    throw std::invalid_argument("options.road_lateral picks the track of an OpenCRG road (.crg); '" + file +
                                "' is not one (leave it 0)");
  RoadShape shape;
  try {
    if (ends_with(".rdf"))
      shape = read_road_data_file(file, track);
    else if (ends_with(".csv"))
      shape.points = read_road_csv(file, track);
    else if (crg)
      shape.points = read_opencrg(file, options.road_lateral);
    else
      throw ModelError("road file '" + file +
                       "': name a road data file (.rdf), a CSV profile (.csv) or an OpenCRG road (.crg)");
  } catch (const ModelError&) {
    throw;
  } catch (const std::runtime_error& error) {  // the readers' own errors name the file and line
    throw ModelError(error.what());
  }
  if (shape.kind == RoadShape::Kind::Drum)
    throw ModelError("road file '" + file + "' holds a drum: a tire on a drum is built in a deck (model:surface)");
  if (shape.kind == RoadShape::Kind::Flat) return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level + shape.level));
  const double h = options.heading;
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector2d& point : shape.points)
    points.emplace_back(h * (point.x() + options.road_start), level + point.y());
  if (h < 0.0) std::reverse(points.begin(), points.end());  // x must not decrease along the profile
  return std::make_shared<RoadProfile>(points, options.road_edge_radius);
}

void check_options(const tirefe_options& options) {
  if (!(options.friction >= 0.0 && std::isfinite(options.friction)))
    throw std::invalid_argument("options.friction must be a finite number >= 0");
  if (options.heading != 1 && options.heading != -1)
    throw std::invalid_argument("options.heading must be +1 (along +x) or -1 (along -x)");
  if (!std::isfinite(options.road_start) || !std::isfinite(options.start_z))
    throw std::invalid_argument("options.road_start and options.start_z must be finite");
  if (!std::isfinite(options.road_lateral))
    throw std::invalid_argument(
        "options.road_lateral must be a finite offset from the OpenCRG road's reference line [m]");
  if (options.road_lateral != 0.0 && !(options.road && *options.road))
    throw std::invalid_argument(
        "options.road_lateral picks the track of an OpenCRG road (.crg); the flat road has "
        "none (leave it 0)");
  if (!(options.road_edge_radius >= 0.0 && std::isfinite(options.road_edge_radius)))
    throw std::invalid_argument("options.road_edge_radius must be a finite number >= 0");
  if (options.free_spin != 0 && options.free_spin != 1)
    throw std::invalid_argument("options.free_spin must be 1 (the wheel turns freely) or 0 (the host drives the spin)");
  if (options.road_track && !options.road)
    throw std::invalid_argument(std::string("options.road_track is \"") + options.road_track +
                                "\" but options.road names no road file: give both, or neither");
}

std::unique_ptr<OpenTire> open_tire(const char* source, const std::vector<ParameterValue>& overrides,
                                    const tirefe_options& options) {
  check_options(options);
  const TireParameters parameters = macros::load_tire_parameters(source, overrides);
  auto handle = std::make_unique<OpenTire>();
  const TireOnRoad::RoadMaker road =
      options.road && *options.road
          ? TireOnRoad::RoadMaker([&options](double level) { return file_road(options, level); })
          : flat_road();
  handle->tire = std::make_unique<TireOnRoad>(parameters, road, RoadContact{options.friction});
  if (options.start_z != 0.0) {
    try {
      handle->tire->press(-options.start_z);
    } catch (const StepFailure& failure) {
      throw ModelError("the tire cannot be pressed to z = " + std::to_string(options.start_z) +
                       " m: " + failure.what());
    }
  }
  IntegratorParameters scheme;
  scheme.alpha = options.hht_alpha;
  scheme.rho_inf = options.rho_inf;
  const Integrator integrator = options.integrator && *options.integrator
                                    ? make_integrator(options.integrator, scheme)
                                    : Integrator::hht_or_average_acceleration(options.hht_alpha);
  handle->spindle = &handle->tire->drive(integrator, options.free_spin ? SpinMode::Free : SpinMode::Driven);
  handle->analysis = &handle->tire->analysis();
  handle->spindle_node = handle->tire->tire().spindle;
  handle->heading = options.heading == 1 ? Heading::PlusX : Heading::MinusX;
  return handle;
}

/// The tire a deck names in its global host_tire (read in a protected call).
struct HostTire {
  macros::DeckModel* deck = nullptr;
  int node = -1;
  bool free_spin = true;
  Heading heading = Heading::PlusX;
};

int read_host_tire(lua_State* L) {
  auto* host = static_cast<HostTire*>(lua_touserdata(L, 1));
  if (lua_getglobal(L, "host_tire") != LUA_TTABLE)
    throw ModelError(
        "the deck names no tire for the host: end it with host_tire = { model = model, spindle = tire.spindle }");
  lua_getfield(L, -1, "model");
  host->deck = &macros::check_model(L, -1);
  lua_getfield(L, -2, "spindle");
  if (!lua_isinteger(L, -1)) throw ModelError("host_tire.spindle must be the tire's spindle node (tire.spindle)");
  host->node = macros::deck_node(*host->deck, lua_tointeger(L, -1));
  host->heading = host->deck->wheel_heading(host->node);
  lua_getfield(L, -3, "free_spin");
  host->free_spin = lua_isnil(L, -1) || lua_toboolean(L, -1);
  return 0;
}

std::unique_ptr<OpenTire> open_deck(const std::string& deck, const std::map<std::string, std::string>& overrides,
                                    const std::string& output_dir) {
  auto handle = std::make_unique<OpenTire>();
  handle->deck = std::make_unique<DeckHold>();
  macros::DeckSession& session = handle->deck->session;
  session.output_dir = output_dir;
  session.quiet = true;
  session.deck_path = deck;
  handle->deck->sandbox = std::make_unique<macros::LuaSandbox>(macros::lua_module_dir());
  macros::LuaSandbox& sandbox = *handle->deck->sandbox;
  macros::install_macros(sandbox, session);
  sandbox.run_file(deck, overrides);
  HostTire host;
  lua_State* L = sandbox.state();
  lua_pushcfunction(L, macros::protected_call<read_host_tire>);
  lua_pushlightuserdata(L, &host);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
    const std::string message = lua_tostring(L, -1);
    lua_pop(L, 1);
    throw ModelError(deck + ": " + message);
  }
  handle->analysis = &host.deck->analysis();
  handle->spindle_node = host.node;
  handle->heading = host.heading;
  handle->deck_spindle =
      std::make_unique<TireSpindle>(*handle->analysis, host.node, host.free_spin ? SpinMode::Free : SpinMode::Driven);
  handle->spindle = handle->deck_spindle.get();
  return handle;
}

/// The reply in wheel axes: the force the tire exerts on the wheel and its Jacobian.
void copy_reply(const SpindleReply& reply, Heading heading, double jacobian_scale, tirefe_spindle_force& out) {
  const Eigen::Vector3d force = wheel_load_from_reaction(force_of(reply), heading);
  const Eigen::Matrix3d jacobian = wheel_load_jacobian(jacobian_of(reply), heading) * jacobian_scale;
  for (int i = 0; i < 3; ++i) {
    out.force[i] = force[i];
    for (int j = 0; j < 3; ++j) out.jacobian[i][j] = jacobian(i, j);
  }
  out.time = reply.time;
  out.newton_iterations = reply.newton_iterations;
}

/// The shortest step a host may ask for. The inertia forces of a step are the change of
/// position over h^2: below this, the round-off of the positions (1e-16 of the tire's
/// size) over h^2 swamps them (h = 1e-12 gave Fz = 3e21 N for a spindle held still).
constexpr double kMinTimeStep = 1e-7;

/// Why 'h' is no time step for a host, or "".
std::string time_step_problem(double h) {
  char text[112] = "";
  if (!(h > 0.0 && std::isfinite(h)))
    std::snprintf(text, sizeof text, "the time step must be a finite number > 0 (got %g)", h);
  else if (h < kMinTimeStep)
    std::snprintf(text, sizeof text, "the time step %g s is below %g s, where round-off swamps the tire's inertia", h,
                  kMinTimeStep);
  return text;
}

bool finite(const double* values, int count) {
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(values[i])) return false;
  return true;
}

/// Solves the trial step to 'input'; the handle then holds a trial until commit or revert.
tirefe_status solve(OpenTire& tire, const SpindleInput& input, double jacobian_scale, tirefe_spindle_force& out) {
  if (const std::string problem = time_step_problem(input.time_step); !problem.empty())
    return refuse(tire, TIREFE_INVALID_ARGUMENT, problem);
  tire.has_trial = false;
  const BudgetWatch::Clock::time_point start = BudgetWatch::Clock::now();
  try {
    copy_reply(tire.spindle->solve_step(input), tire.heading, jacobian_scale, out);
  } catch (...) {
    tire.budget.solved(BudgetWatch::seconds_since(start), nullptr);
    throw;
  }
  tire.budget.solved(BudgetWatch::seconds_since(start), &tire.analysis->last_newton_report());
  tire.has_trial = true;
  return TIREFE_OK;
}

/// Committed displacement, velocity and acceleration of the spindle's DOF c of the plane.
struct DofState {
  double u, v, a;
};
DofState committed_dof(const OpenTire& tire, int c) {
  const State& state = tire.analysis->state();
  const int dof = dof_index(tire.spindle_node, c);
  return {state.displacement[dof], state.velocity[dof], state.acceleration[dof]};
}

/// A stretch of tirefe_advance for the step controller: every step it tries puts the
/// spindle where the path's cubic is at the step's end, and is committed once it converges.
/// Its clock starts at 0 with the stretch, so that what it says speaks of the stretch alone.
class SpindlePath final : public SteppedSystem {
 public:
  SpindlePath(OpenTire& tire, const tirefe_spindle_path& path)
      : tire_(tire),
        start_(tire.spindle->time()),
        duration_(path.duration),
        start_position_(plane_motion(tire.spindle->committed_position(), tire.heading)),
        start_rate_(path.start_velocity),
        end_(path.position),
        end_rate_(path.velocity) {}

  double time() const override { return tire_.spindle->time() - start_; }

  /// tirefe_cancel, seen between the stretch's steps.
  struct Cancelled : std::runtime_error {
    using std::runtime_error::runtime_error;
  };

  bool try_step(double step, double end_time, StepRecord& record) override {
    if (macros::stop_signal().load() == macros::kHostCancel)
      throw Cancelled("stopped by tirefe_cancel " + where() + ", at its last committed step");
    const Eigen::Vector3d plane = plane_motion(position_at(end_time), tire_.heading);
    SpindleInput input{step, plane.x(), plane.y(), plane.z()};
    input.jacobian = false;  // nobody reads it
    const BudgetWatch::Clock::time_point start = BudgetWatch::Clock::now();
    try {
      record.newton_iterations = tire_.spindle->solve_step(input).newton_iterations;
    } catch (const StepFailure&) {
      tire_.budget.solved(BudgetWatch::seconds_since(start), nullptr);
      failed_at_ = end_time;
      ++report_.cuts;
      return false;
    }
    tire_.budget.solved(BudgetWatch::seconds_since(start), &tire_.analysis->last_newton_report());
    report_.newton_iterations += record.newton_iterations;
    return true;
  }

  void commit_step(double step, StepRecord& record) override {
    const BudgetWatch::Clock::time_point start = BudgetWatch::Clock::now();
    tire_.spindle->commit();
    tire_.budget.committed(BudgetWatch::seconds_since(start));
    record.time = time();
    record.step_size = step;
    ++report_.steps;
  }

  std::string failure_message(int cuts, double step) const override {
    std::ostringstream message;
    message << "the spindle's path could not be followed " << failed_at_ << " s into its " << duration_
            << " s, even after " << cuts << " cuts (smallest dt = " << step
            << " s): " << tire_.analysis->last_failure();
    return message.str();
  }

  std::string where() const override {
    std::ostringstream text;
    text << time() << " s into its " << duration_ << " s";
    return text.str();
  }

  /// The steps and tries so far, at the committed time.
  tirefe_advance_report report() const {
    tirefe_advance_report report = report_;
    report.time = tire_.spindle->time();
    return report;
  }

 private:
  /// Where the cubic that meets the committed motion and the path's end puts the spindle at 'time'.
  Eigen::Vector3d position_at(double time) const {
    const double s = std::clamp(time / duration_, 0.0, 1.0), T = duration_;
    const double h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s), h10 = s * (1.0 - s) * (1.0 - s);
    const double h01 = s * s * (3.0 - 2.0 * s), h11 = s * s * (s - 1.0);
    return h00 * start_position_ + h10 * T * start_rate_ + h01 * end_ + h11 * T * end_rate_;
  }

  OpenTire& tire_;
  double start_, duration_;
  Eigen::Vector3d start_position_, start_rate_, end_, end_rate_;
  double failed_at_ = 0.0;
  tirefe_advance_report report_{};
};

}  // namespace

extern "C" {

const char* tirefe_version(void) {
  static const std::string version = std::string(kVersion) + " (" + kGitCommit + ")";
  return version.c_str();
}

void tirefe_default_options(tirefe_options* options) {
  if (!options) return;
  options->friction = 0.8;
  options->hht_alpha = 0.0;
  options->free_spin = 1;
  options->heading = 1;
  options->road = nullptr;
  options->road_track = nullptr;
  options->road_lateral = 0.0;
  options->road_start = 0.0;
  options->road_edge_radius = 0.0;
  options->start_z = 0.0;
  options->integrator = nullptr;
  options->rho_inf = 0.9;
}

tirefe_status tirefe_open(const char* source, const tirefe_parameter* overrides, size_t count,
                          const tirefe_options* options, tirefe_tire** tire, char* error, size_t error_size) {
  if (tire) *tire = nullptr;
  if (!source || !tire || (count > 0 && !overrides)) {
    copy_message("tirefe_open: source and tire must not be NULL, nor overrides when count > 0", error, error_size);
    return TIREFE_INVALID_ARGUMENT;
  }
  tirefe_options chosen;
  tirefe_default_options(&chosen);
  if (options) chosen = *options;
  const tirefe_status status = without_handle(error, error_size, [&] {
    std::shared_ptr<OpenTire> opened(open_tire(source, parameter_values(overrides, count), chosen).release(),
                                     delete_tire);
    *tire = open_tires().add(std::move(opened));
  });
  // Building the tire is not a step: a failure to inflate it is the parameters' fault.
  return answer_cancel(status == TIREFE_STEP_FAILED ? TIREFE_MODEL_ERROR : status);
}

tirefe_status tirefe_static_forces(const char* source, const tirefe_parameter* overrides, size_t count,
                                   const double* deflections, size_t n, double* forces, char* error,
                                   size_t error_size) {
  if (!source || (count > 0 && !overrides) || (n > 0 && (!deflections || !forces))) {
    copy_message("tirefe_static_forces: source, overrides, deflections and forces must not be NULL", error, error_size);
    return TIREFE_INVALID_ARGUMENT;
  }
  return answer_cancel(without_handle(error, error_size, [&] {
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(deflections[i]))
        throw std::invalid_argument("deflection " + std::to_string(i) + " is not a finite number");
    size_t pressed = 0;
    const std::vector<double> curve = static_vertical_forces(
        macros::load_tire_parameters(source, parameter_values(overrides, count)), {deflections, deflections + n}, [&] {
          if (macros::stop_signal().load() == macros::kHostCancel)
            throw ModelError("stopped by tirefe_cancel after " + std::to_string(pressed) + " of " + std::to_string(n) +
                             " deflections");
          ++pressed;
        });
    std::copy(curve.begin(), curve.end(), forces);
  }));
}

tirefe_status tirefe_open_deck(const char* deck, const char* const* overrides, size_t count, const char* output_dir,
                               tirefe_tire** tire, char* error, size_t error_size) {
  if (tire) *tire = nullptr;
  if (!deck || !tire || (count > 0 && !overrides)) {
    copy_message("tirefe_open_deck: deck and tire must not be NULL, nor overrides when count > 0", error, error_size);
    return TIREFE_INVALID_ARGUMENT;
  }
  if (output_dir && !*output_dir) {
    copy_message("tirefe_open_deck: output_dir is empty: name a folder, or give NULL for \"results\"", error,
                 error_size);
    return TIREFE_INVALID_ARGUMENT;
  }
  const tirefe_status status = without_handle(error, error_size, [&] {
    std::map<std::string, std::string> values;
    for (size_t i = 0; i < count; ++i) {
      if (!overrides[i]) throw std::invalid_argument("override " + std::to_string(i) + " is NULL");
      const std::string pair = overrides[i];
      const size_t equals = pair.find('=');
      if (equals == std::string::npos || equals == 0)
        throw std::invalid_argument("override '" + pair + "' is not key=value");
      if (!values.emplace(pair.substr(0, equals), pair.substr(equals + 1)).second)
        throw std::invalid_argument("override '" + pair.substr(0, equals) + "' is given twice");
    }
    std::unique_ptr<OpenTire> opened;
    {
      const std::lock_guard<std::mutex> lock(deck_tires_mutex);
      opened = open_deck(deck, values, output_dir ? output_dir : "results");
    }
    // delete_tire takes the lock: the table's owner is made after it is released.
    *tire = open_tires().add(std::shared_ptr<OpenTire>(opened.release(), delete_tire));
  });
  // A deck's errors (already "deck.lua:LINE: ...") and failed steps are the deck's fault.
  return answer_cancel(status == TIREFE_STEP_FAILED || status == TIREFE_INTERNAL_ERROR ? TIREFE_MODEL_ERROR : status);
}

void tirefe_cancel(void) { macros::stop_signal().store(macros::kHostCancel); }

tirefe_status tirefe_close(tirefe_tire* tire) {
  if (!tire) return TIREFE_OK;
  return open_tires().remove(tire) ? TIREFE_OK : TIREFE_INVALID_ARGUMENT;  // freed here, or by a call still on it
}

const char* tirefe_message(const tirefe_tire* tire) {
  if (!tire) return "no tire (NULL handle)";
  const std::shared_ptr<OpenTire> open = open_tires().find(tire);
  // The text lives in the tire, which the table keeps until tirefe_close.
  return open ? open->message.c_str() : kNotATire;
}

tirefe_status tirefe_road_level(tirefe_tire* tire, double* level) {
  return guarded(tire, [&](OpenTire& t) {
    if (!level) return refuse(t, TIREFE_INVALID_ARGUMENT, "level must not be NULL");
    if (!t.tire) return refuse(t, TIREFE_INVALID_CALL, "a deck's tire: its roads are the deck's own");
    *level = t.tire->road_level();
    return TIREFE_OK;
  });
}

tirefe_status tirefe_solve(tirefe_tire* tire, const tirefe_spindle_motion* motion, tirefe_spindle_force* out) {
  return guarded(tire, [&](OpenTire& t) {
    if (!motion || !out) return refuse(t, TIREFE_INVALID_ARGUMENT, "motion and out must not be NULL");
    const double values[] = {motion->x, motion->z, motion->spin};
    if (!finite(values, 3)) return refuse(t, TIREFE_INVALID_ARGUMENT, "the spindle motion must be finite");
    const Eigen::Vector3d plane = plane_motion(Eigen::Vector3d(values), t.heading);
    return solve(t, SpindleInput{motion->time_step, plane.x(), plane.y(), plane.z()}, 1.0, *out);
  });
}

tirefe_status tirefe_solve_velocity(tirefe_tire* tire, double time_step, const double velocity[3],
                                    tirefe_spindle_force* out) {
  return guarded(tire, [&](OpenTire& t) {
    if (!velocity || !out) return refuse(t, TIREFE_INVALID_ARGUMENT, "velocity and out must not be NULL");
    if (!finite(velocity, 3)) return refuse(t, TIREFE_INVALID_ARGUMENT, "the spindle velocity must be finite");
    if (const std::string problem = time_step_problem(time_step); !problem.empty())
      return refuse(t, TIREFE_INVALID_ARGUMENT, problem);
    const TimeScheme& scheme = t.analysis->integrator().scheme();
    const double h = time_step;
    const Eigen::Vector2d& reference = t.analysis->model().mesh().position(t.spindle_node);
    const Eigen::Vector3d plane_velocity = plane_motion(Eigen::Vector3d(velocity), t.heading);
    double position[3];
    for (int c = 0; c < 3; ++c) {
      const DofState now = committed_dof(t, c);
      position[c] = scheme.displacement_for_velocity(now.u, now.v, now.a, plane_velocity[c], h);
    }
    const SpindleInput input{h, reference.x() + position[0], reference.y() + position[1], position[2]};
    return solve(t, input, scheme.displacement_per_velocity(h), *out);
  });
}

tirefe_status tirefe_advance(tirefe_tire* tire, const tirefe_spindle_path* path, double max_step,
                             tirefe_advance_report* report) {
  const tirefe_status status = guarded(tire, [&](OpenTire& t) {
    if (!path) return refuse(t, TIREFE_INVALID_ARGUMENT, "path must not be NULL");
    if (!(path->duration > 0.0 && std::isfinite(path->duration)) || !(max_step > 0.0 && std::isfinite(max_step)))
      return refuse(t, TIREFE_INVALID_ARGUMENT, "the path's duration and max_step must be finite numbers > 0");
    if (!finite(path->start_velocity, 3) || !finite(path->position, 3) || !finite(path->velocity, 3))
      return refuse(t, TIREFE_INVALID_ARGUMENT, "the path's rates and end position must be finite");
    // Equal steps that end on the stretch's end: a step's size changing from one to the next
    // sets the tire's contact patch ringing (rolling fast, its Fx), so every stretch starts
    // afresh with them, only cut where they do not converge.
    const double count = std::ceil(path->duration / max_step * (1.0 - 1e-12));
    if (const std::string problem = time_step_problem(path->duration / count); !problem.empty()) {
      std::ostringstream text;
      text << "a path of " << path->duration << " s in steps of at most " << max_step << " s: " << problem;
      return refuse(t, TIREFE_INVALID_ARGUMENT, text.str());
    }
    if (t.has_trial) t.spindle->revert();
    t.has_trial = false;
    StepSizes sizes{path->duration / count, path->duration / count};
    SpindlePath stretch(t, *path);
    StepController controller(sizes);
    tirefe_status status = TIREFE_OK;
    try {
      controller.advance_to(stretch, path->duration);
    } catch (const StepFailure& failure) {
      status = refuse(t, TIREFE_STEP_FAILED, failure.what());
    } catch (const SpindlePath::Cancelled& stop) {
      status = refuse(t, TIREFE_CANCELLED, stop.what());
    }
    if (report) *report = stretch.report();
    return status;
  });
  return answer_cancel(status);
}

tirefe_status tirefe_commit(tirefe_tire* tire) {
  return guarded(tire, [](OpenTire& t) {
    if (!t.has_trial) return refuse(t, TIREFE_INVALID_CALL, "tirefe_commit: no solved trial step to accept");
    t.has_trial = false;
    const BudgetWatch::Clock::time_point start = BudgetWatch::Clock::now();
    t.spindle->commit();
    t.budget.committed(BudgetWatch::seconds_since(start));
    return TIREFE_OK;
  });
}

tirefe_status tirefe_revert(tirefe_tire* tire) {
  return guarded(tire, [](OpenTire& t) {
    t.has_trial = false;
    t.budget.forget();
    t.spindle->revert();
    return TIREFE_OK;
  });
}

tirefe_status tirefe_state(tirefe_tire* tire, tirefe_spindle_state* state) {
  return guarded(tire, [&](OpenTire& t) {
    if (!state) return refuse(t, TIREFE_INVALID_ARGUMENT, "state must not be NULL");
    const Eigen::Vector3d position = plane_motion(t.spindle->committed_position(), t.heading);
    const Eigen::Vector3d velocity(committed_dof(t, 0).v, committed_dof(t, 1).v, committed_dof(t, 2).v);
    const Eigen::Vector3d wheel_velocity = plane_motion(velocity, t.heading);
    const Eigen::Vector3d force = wheel_load_from_reaction(t.spindle->committed_force(), t.heading);
    state->time = t.spindle->time();
    for (int c = 0; c < 3; ++c) {
      state->position[c] = position[c];
      state->velocity[c] = wheel_velocity[c];
      state->force[c] = force[c];
    }
    return TIREFE_OK;
  });
}

tirefe_status tirefe_set_step_budget(tirefe_tire* tire, const tirefe_step_budget* budget) {
  return guarded(tire, [&](OpenTire& t) {
    const tirefe_step_budget chosen = budget ? *budget : tirefe_step_budget{0, 0.0, 0.0};
    if (chosen.max_iterations < 0)
      return refuse(t, TIREFE_INVALID_ARGUMENT, "budget.max_iterations must be >= 0 (0: Newton to convergence)");
    if (!(chosen.max_time >= 0.0 && std::isfinite(chosen.max_time)))
      return refuse(t, TIREFE_INVALID_ARGUMENT, "budget.max_time must be a finite number >= 0 [s] (0: none)");
    if (!(chosen.max_residual >= 0.0))
      return refuse(t, TIREFE_INVALID_ARGUMENT, "budget.max_residual must be a number >= 0 (0: 1e-4)");
    t.budget.set(chosen, *t.analysis);
    return TIREFE_OK;
  });
}

tirefe_status tirefe_step_budget_report(tirefe_tire* tire, tirefe_budget_report* report) {
  return guarded(tire, [&](OpenTire& t) {
    if (!report) return refuse(t, TIREFE_INVALID_ARGUMENT, "report must not be NULL");
    *report = t.budget.report();
    return TIREFE_OK;
  });
}

tirefe_status tirefe_save_state(tirefe_tire* tire, tirefe_saved_state** saved) {
  if (saved) *saved = nullptr;
  return guarded(tire, [&](OpenTire& t) {
    if (!saved) return refuse(t, TIREFE_INVALID_ARGUMENT, "saved must not be NULL");
    if (t.deck) return refuse(t, TIREFE_INVALID_CALL, "a deck's tire is saved with the deck's model:checkpoint");
    auto state =
        std::make_shared<SavedState>(SavedState{macros::capture_checkpoint(*t.analysis, nullptr, 1, "tirefe C API")});
    *saved = saved_states().add(std::move(state));
    return TIREFE_OK;
  });
}

tirefe_status tirefe_restore_state(tirefe_tire* tire, const tirefe_saved_state* saved) {
  return guarded(tire, [&](OpenTire& t) {
    const std::shared_ptr<SavedState> state = saved_states().find(saved);
    if (!state)
      return refuse(
          t, TIREFE_INVALID_ARGUMENT,
          saved ? "saved is no state of tirefe_save_state (freed, or never saved)" : "saved must not be NULL");
    if (t.has_trial) t.spindle->revert();
    t.has_trial = false;
    t.budget.forget();
    if (t.deck) return refuse(t, TIREFE_INVALID_CALL, "a deck's tire is restored with tirefe --restart");
    const int nodes = t.analysis->model().mesh().node_count();
    if (state->checkpoint.node_count != nodes)
      return refuse(t, TIREFE_INVALID_ARGUMENT,
                    "saved is the state of another tire (of " + std::to_string(state->checkpoint.node_count) +
                        " nodes, this one has " + std::to_string(nodes) +
                        "): restore a state into a tire built with the same parameters");
    macros::restore_checkpoint(state->checkpoint, *t.analysis, nullptr);
    return TIREFE_OK;
  });
}

tirefe_status tirefe_free_state(tirefe_saved_state* saved) {
  if (!saved) return TIREFE_OK;
  return saved_states().remove(saved) ? TIREFE_OK : TIREFE_INVALID_ARGUMENT;
}

}  // extern "C"
