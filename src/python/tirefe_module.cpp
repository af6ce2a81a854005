// The compiled part of the Python package `tirefe` (pybind11): tirefe._core. The tire
// behind its spindle as a class over the C API (include/tirefe.h), forces and Jacobians as
// numpy arrays; a deck run with parameters; the static vertical curve; and the FMI 2.0
// calls of a co-simulation FMU loaded with dlopen, which tirefe/fmu.py drives
// (docs/python.md).
#include <dlfcn.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <unordered_set>
#include <vector>

#include "fmu/fmi2.h"
#include "app/deck_runner.hpp"
#include "macros/macro_table.hpp"
#include "tirefe.h"
#include "tirefe/version.hpp"
#include "vehicle/tire_on_road.hpp"

namespace py = pybind11;

namespace {

// The package's exceptions (their Python classes are made in the module below).
PyObject* step_failed_type = nullptr;
PyObject* model_error_type = nullptr;

/// Raises the Python exception of a failed C call; 'message' is read after the call.
[[noreturn]] void raise_status(tirefe_status status, const std::string& message) {
  PyObject* type = status == TIREFE_STEP_FAILED        ? step_failed_type
                   : status == TIREFE_MODEL_ERROR      ? model_error_type
                   : status == TIREFE_OUT_OF_MEMORY    ? PyExc_MemoryError
                   : status == TIREFE_INVALID_ARGUMENT ? PyExc_ValueError
                                                       : PyExc_RuntimeError;
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

void check(tirefe_status status, const char* message) {
  if (status != TIREFE_OK) raise_status(status, message);
}

std::vector<tirefe_parameter> parameter_list(const std::map<std::string, double>& parameters) {
  std::vector<tirefe_parameter> overrides;
  for (const auto& [name, value] : parameters) overrides.push_back({name.c_str(), value});
  return overrides;
}

py::array_t<double> vector(const double (&values)[3]) {
  py::array_t<double> array(3);
  for (int i = 0; i < 3; ++i) array.mutable_at(i) = values[i];
  return array;
}

/// The objects of class T whose constructor ran: pybind11 hands a method of one made by
/// T.__new__ alone raw memory, or none, which is none of them.
template <class T>
std::unordered_set<const T*>& constructed() {
  static std::unordered_set<const T*> objects;
  return objects;
}

class Tire {
 public:
  static constexpr const char* kUninitialized =
      "this tirefe.Tire was not initialized: make tires with tirefe.Tire(...)";

  Tire(const std::string& source, const std::map<std::string, double>& parameters, double friction, double hht_alpha,
       bool free_spin, const std::string& heading, const std::optional<std::string>& road,
       const std::optional<std::string>& road_track, double road_lateral, double road_start, double road_edge_radius,
       double start_z, int max_iterations, double max_time, double max_residual,
       const std::optional<std::string>& integrator, double rho_inf) {
    tirefe_options options;
    tirefe_default_options(&options);
    options.friction = friction;
    options.hht_alpha = hht_alpha;
    options.free_spin = free_spin ? 1 : 0;
    if (heading != "+x" && heading != "-x")
      throw py::value_error("heading must be \"+x\" or \"-x\", not \"" + heading + "\"");
    options.heading = heading == "+x" ? 1 : -1;
    options.road = road ? road->c_str() : nullptr;
    options.road_track = road_track ? road_track->c_str() : nullptr;
    options.road_lateral = road_lateral;
    options.road_start = road_start;
    options.road_edge_radius = road_edge_radius;
    options.start_z = start_z;
    options.integrator = integrator ? integrator->c_str() : nullptr;
    options.rho_inf = rho_inf;
    const std::vector<tirefe_parameter> overrides = parameter_list(parameters);
    char error[512] = "";
    tirefe_status status;
    {
      py::gil_scoped_release unlocked;
      status = tirefe_open(source.c_str(), overrides.data(), overrides.size(), &options, &tire_, error, sizeof error);
    }
    check(status, error);
    if (max_iterations != 0 || max_time != 0.0 || max_residual != 0.0) {
      const tirefe_step_budget budget{max_iterations, max_time, max_residual};
      if (tirefe_set_step_budget(tire_, &budget) != TIREFE_OK) {
        const std::string message = tirefe_message(tire_);
        tirefe_close(tire_);
        throw py::value_error(message);
      }
    }
    constructed<Tire>().insert(this);
  }
  ~Tire() {
    constructed<Tire>().erase(this);
    tirefe_close(tire_);
  }
  Tire(const Tire&) = delete;
  Tire& operator=(const Tire&) = delete;

  void close() {
    tirefe_close(tire_);
    tire_ = nullptr;
  }

  py::dict budget_report() {
    tirefe_budget_report report{};
    check_call(tirefe_step_budget_report(open(), &report));
    py::dict answer;
    answer["steps"] = report.steps;
    answer["unconverged"] = report.unconverged;
    answer["worst_residual"] = report.worst_residual;
    answer["overruns"] = report.overruns;
    answer["time_misses"] = report.time_misses;
    answer["worst_time"] = report.worst_time;
    return answer;
  }

  py::tuple solve(double time_step, double x, double z, double spin) {
    const tirefe_spindle_motion motion{time_step, x, z, spin};
    tirefe_spindle_force out;
    tirefe_status status;
    {
      py::gil_scoped_release unlocked;  // other Python threads run while the tire solves
      status = tirefe_solve(open(), &motion, &out);
    }
    check_call(status);
    return reply(out);
  }
  py::tuple solve_velocity(double time_step, double vx, double vz, double spin_rate) {
    const double velocity[3] = {vx, vz, spin_rate};
    tirefe_spindle_force out;
    tirefe_status status;
    {
      py::gil_scoped_release unlocked;
      status = tirefe_solve_velocity(open(), time_step, velocity, &out);
    }
    check_call(status);
    return reply(out);
  }
  py::dict advance(double duration, const std::array<double, 3>& start_velocity, const std::array<double, 3>& position,
                   const std::array<double, 3>& velocity, double max_step) {
    tirefe_spindle_path path{duration,
                             {start_velocity[0], start_velocity[1], start_velocity[2]},
                             {position[0], position[1], position[2]},
                             {velocity[0], velocity[1], velocity[2]}};
    tirefe_advance_report report{};
    tirefe_status status;
    {
      py::gil_scoped_release unlocked;
      status = tirefe_advance(open(), &path, max_step, &report);
    }
    check_call(status);
    py::dict result;
    result["time"] = report.time;
    result["steps"] = report.steps;
    result["cuts"] = report.cuts;
    result["newton_iterations"] = report.newton_iterations;
    return result;
  }
  void commit() { check_call(tirefe_commit(open())); }
  void revert() { check_call(tirefe_revert(open())); }
  py::dict state() {
    tirefe_spindle_state state;
    check_call(tirefe_state(open(), &state));
    py::dict result;
    result["time"] = state.time;
    result["position"] = vector(state.position);
    result["velocity"] = vector(state.velocity);
    result["force"] = vector(state.force);
    return result;
  }
  double road_level() {
    double level = 0.0;
    check_call(tirefe_road_level(open(), &level));
    return level;
  }

 private:
  tirefe_tire* open() const {
    if (!tire_) throw py::value_error("the tire is closed");
    return tire_;
  }
  /// The message is read after the call that set it (it lives in the handle until the next call).
  void check_call(tirefe_status status) const { check(status, tirefe_message(tire_)); }
  static py::tuple reply(const tirefe_spindle_force& out) {
    py::array_t<double> jacobian({3, 3});
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) jacobian.mutable_at(i, j) = out.jacobian[i][j];
    return py::make_tuple(vector(out.force), jacobian);
  }

  tirefe_tire* tire_ = nullptr;
};

/// A method bound so that an object whose __init__ never ran (T.__new__(T)) raises
/// instead of being followed.
template <class T, class Result, class... Arguments>
auto method(Result (T::*function)(Arguments...)) {
  return [function](T* self, Arguments... arguments) -> Result {
    if (!constructed<T>().count(self)) throw py::type_error(T::kUninitialized);
    return (self->*function)(arguments...);
  };
}

/// The static vertical curve of the C API's tirefe_static_forces, stopping for Ctrl-C
/// between presses (KeyboardInterrupt).
py::array_t<double> static_forces(const std::string& source, const std::map<std::string, double>& parameters,
                                  const std::vector<double>& deflections) {
  for (double deflection : deflections)
    if (!std::isfinite(deflection)) throw py::value_error("the deflections must be finite");
  for (const auto& [name, value] : parameters)
    if (!std::isfinite(value)) throw py::value_error("parameter '" + name + "' is not a finite number");
  std::vector<tirefe::macros::ParameterValue> overrides(parameters.begin(), parameters.end());
  std::vector<double> forces;
  {
    py::gil_scoped_release unlocked;
    try {
      forces = tirefe::static_vertical_forces(tirefe::macros::load_tire_parameters(source, overrides), deflections, [] {
        py::gil_scoped_acquire locked;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      });
    } catch (const tirefe::ModelError& error) {
      py::gil_scoped_acquire locked;
      raise_status(TIREFE_MODEL_ERROR, error.what());
    } catch (const tirefe::StepFailure& failure) {
      py::gil_scoped_acquire locked;
      raise_status(TIREFE_MODEL_ERROR, failure.what());
    }
  }
  return py::array_t<double>(static_cast<py::ssize_t>(forces.size()), forces.data());
}

/// Runs a deck as `tirefe DECK key=value ... --output-dir DIR --quiet` would, in this
/// process. Ctrl-C or SIGTERM stop the run after its step (its files closed) and are then
/// handed on to Python's handlers (KeyboardInterrupt for Ctrl-C).
py::dict run_deck(const std::string& deck, const std::map<std::string, py::object>& parameters,
                  const std::string& output_dir) {
  // Every argument stays what it is: a path starting with '-' is no option, a parameter's
  // name no other argument.
  const auto path = [](const std::string& name, const char* what) {
    if (name.empty()) throw py::value_error(std::string(what) + " is empty: give a path");
    return name[0] == '-' ? "./" + name : name;
  };
  std::vector<std::string> arguments{"tirefe", path(deck, "deck")};
  for (const auto& [name, value] : parameters) {
    const bool plain = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                       std::all_of(name.begin(), name.end(),
                                   [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!plain)
      throw py::value_error("parameter name '" + name +
                            "' is no name a deck declares (letters, digits and '_', e.g. end_time)");
    arguments.push_back(name + "=" + std::string(py::str(value)));
  }
  arguments.insert(arguments.end(), {"--output-dir", path(output_dir, "output_dir"), "--quiet"});
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  // The GIL stays held: no two decks write HDF5 files at once (the library is not thread-safe).
  const tirefe::macros::DeckOutcome outcome =
      tirefe::macros::run_deck_command(static_cast<int>(argv.size()), argv.data(), {});
  if (outcome.status == 128 + SIGINT || outcome.status == 128 + SIGTERM) {
    std::raise(outcome.status - 128);  // to the handler the run had replaced
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  std::vector<std::string> files;
  for (const std::string& file : outcome.files)
    if (file.size() > 3 && file.compare(file.size() - 3, 3, ".h5") == 0) files.push_back(file);
  py::dict result;
  result["status"] = outcome.status;
  result["error"] = outcome.error;
  result["files"] = files;
  return result;
}

/// The FMI 2.0 co-simulation functions of one FMU binary and one instance of it; its
/// logger's messages are kept for Python (tirefe.Fmu reads them).
class FmiInstance {
 public:
  static constexpr const char* kUninitialized =
      "this FmiInstance was not initialized: make it with FmiInstance(...) (tirefe.Fmu does)";

  FmiInstance(const std::string& binary, const std::string& guid, const std::string& resource_uri,
              const std::string& name, bool logging) {
    library_ = dlopen(binary.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library_) throw std::runtime_error("cannot load the FMU's binary " + binary + ": " + dlerror());
    try {
      instantiate(guid, resource_uri, name, logging);
    } catch (...) {
      free_instance();  // the destructor of an object never made does not run
      throw;
    }
    constructed<FmiInstance>().insert(this);
  }
  ~FmiInstance() {
    constructed<FmiInstance>().erase(this);
    free_instance();
  }
  FmiInstance(const FmiInstance&) = delete;
  FmiInstance& operator=(const FmiInstance&) = delete;

  /// The constructor's work once the binary is loaded: its functions, then the instance.
  void instantiate(const std::string& guid, const std::string& resource_uri, const std::string& name, bool logging) {
    load("fmi2Instantiate", instantiate_);
    load("fmi2FreeInstance", free_instance_);
    load("fmi2SetupExperiment", setup_experiment_);
    load("fmi2EnterInitializationMode", enter_initialization_);
    load("fmi2ExitInitializationMode", exit_initialization_);
    load("fmi2Terminate", terminate_);
    load("fmi2Reset", reset_);
    load("fmi2GetReal", get_real_);
    load("fmi2SetReal", set_real_);
    load("fmi2GetInteger", get_integer_);
    load("fmi2SetInteger", set_integer_);
    load("fmi2GetBoolean", get_boolean_);
    load("fmi2SetBoolean", set_boolean_);
    load("fmi2GetString", get_string_);
    load("fmi2SetString", set_string_);
    load("fmi2DoStep", do_step_);
    load("fmi2GetRealStatus", get_real_status_);
    load("fmi2GetBooleanStatus", get_boolean_status_);
    callbacks_ = new fmi2CallbackFunctions{&FmiInstance::logger, std::calloc, std::free, nullptr, this};
    instance_ = instantiate_(name.c_str(), fmi2CoSimulation, guid.c_str(), resource_uri.c_str(), callbacks_, fmi2False,
                             logging ? fmi2True : fmi2False);
    if (!instance_) throw std::runtime_error("fmi2Instantiate failed: " + messages_text());
  }

  void free_instance() {
    if (instance_) free_instance_(instance_);
    instance_ = nullptr;
    delete callbacks_;
    callbacks_ = nullptr;
    if (library_) dlclose(library_);
    library_ = nullptr;
  }

  int setup_experiment(double start, std::optional<double> stop) {
    return setup_experiment_(live(), fmi2False, 0.0, start, stop ? fmi2True : fmi2False, stop.value_or(0.0));
  }
  int enter_initialization_mode() { return enter_initialization_(live()); }
  int exit_initialization_mode() { return exit_initialization_(live()); }
  int terminate() { return terminate_(live()); }
  int reset() { return reset_(live()); }
  int do_step(double time, double step) {
    fmi2Component instance = live();
    py::gil_scoped_release unlocked;
    return do_step_(instance, time, step, fmi2True);
  }
  int set_real(const std::vector<fmi2ValueReference>& references, const std::vector<double>& values) {
    return set_real_(live(), references.data(), same_size(references, values), values.data());
  }
  int set_integer(const std::vector<fmi2ValueReference>& references, const std::vector<int>& values) {
    return set_integer_(live(), references.data(), same_size(references, values), values.data());
  }
  int set_boolean(const std::vector<fmi2ValueReference>& references, const std::vector<bool>& values) {
    std::vector<fmi2Boolean> booleans(values.begin(), values.end());
    return set_boolean_(live(), references.data(), same_size(references, values), booleans.data());
  }
  int set_string(const std::vector<fmi2ValueReference>& references, const std::vector<std::string>& values) {
    std::vector<fmi2String> strings;
    for (const std::string& value : values) strings.push_back(value.c_str());
    return set_string_(live(), references.data(), same_size(references, values), strings.data());
  }
  py::tuple get_real(const std::vector<fmi2ValueReference>& references) {
    std::vector<double> values(references.size());
    const int status = get_real_(live(), references.data(), references.size(), values.data());
    return py::make_tuple(status, values);
  }
  py::tuple get_integer(const std::vector<fmi2ValueReference>& references) {
    std::vector<int> values(references.size());
    const int status = get_integer_(live(), references.data(), references.size(), values.data());
    return py::make_tuple(status, values);
  }
  py::tuple get_boolean(const std::vector<fmi2ValueReference>& references) {
    std::vector<fmi2Boolean> values(references.size());
    const int status = get_boolean_(live(), references.data(), references.size(), values.data());
    std::vector<bool> booleans(values.begin(), values.end());
    return py::make_tuple(status, booleans);
  }
  py::tuple get_string(const std::vector<fmi2ValueReference>& references) {
    std::vector<fmi2String> values(references.size(), nullptr);
    const int status = get_string_(live(), references.data(), references.size(), values.data());
    std::vector<std::string> strings;
    for (fmi2String value : values) strings.push_back(value ? value : "");
    return py::make_tuple(status, strings);
  }
  double last_successful_time() {
    fmi2Real time = 0.0;
    get_real_status_(live(), fmi2LastSuccessfulTime, &time);
    return time;
  }
  bool terminated() {
    fmi2Boolean terminated = fmi2False;
    get_boolean_status_(live(), fmi2Terminated, &terminated);
    return terminated != fmi2False;
  }
  /// The logger's messages since the last call, as (status, category, text).
  std::vector<std::tuple<int, std::string, std::string>> take_messages() {
    std::vector<std::tuple<int, std::string, std::string>> taken;
    taken.swap(messages_);
    return taken;
  }

 private:
  template <class Function>
  void load(const char* name, Function*& function) {
    *reinterpret_cast<void**>(&function) = dlsym(library_, name);
    if (!function) throw std::runtime_error(std::string("the FMU's binary does not export ") + name);
  }
  fmi2Component live() const {
    if (!instance_) throw py::value_error("the FMU instance is freed");
    return instance_;
  }
  template <class A, class B>
  static size_t same_size(const A& references, const B& values) {
    if (references.size() != values.size()) throw py::value_error("as many values as value references, please");
    return references.size();
  }
  std::string messages_text() const {
    std::string text;
    for (const auto& message : messages_) text += (text.empty() ? "" : "; ") + std::get<2>(message);
    return text.empty() ? "no message" : text;
  }
  static void logger(fmi2ComponentEnvironment environment, fmi2String, fmi2Status status, fmi2String category,
                     fmi2String message, ...) {
    va_list arguments, copy;
    va_start(arguments, message);
    va_copy(copy, arguments);
    const int length = std::vsnprintf(nullptr, 0, message, copy);
    va_end(copy);
    std::string text(length > 0 ? static_cast<size_t>(length) : 0, '\0');
    if (length > 0) std::vsnprintf(text.data(), text.size() + 1, message, arguments);
    va_end(arguments);
    static_cast<FmiInstance*>(environment)->messages_.emplace_back(status, category ? category : "", text);
  }

  void* library_ = nullptr;
  fmi2CallbackFunctions* callbacks_ = nullptr;  // on the heap: the FMU may keep the pointer
  fmi2Component instance_ = nullptr;
  std::vector<std::tuple<int, std::string, std::string>> messages_;
  decltype(&fmi2Instantiate) instantiate_ = nullptr;
  decltype(&fmi2FreeInstance) free_instance_ = nullptr;
  decltype(&fmi2SetupExperiment) setup_experiment_ = nullptr;
  decltype(&fmi2EnterInitializationMode) enter_initialization_ = nullptr;
  decltype(&fmi2ExitInitializationMode) exit_initialization_ = nullptr;
  decltype(&fmi2Terminate) terminate_ = nullptr;
  decltype(&fmi2Reset) reset_ = nullptr;
  decltype(&fmi2GetReal) get_real_ = nullptr;
  decltype(&fmi2SetReal) set_real_ = nullptr;
  decltype(&fmi2GetInteger) get_integer_ = nullptr;
  decltype(&fmi2SetInteger) set_integer_ = nullptr;
  decltype(&fmi2GetBoolean) get_boolean_ = nullptr;
  decltype(&fmi2SetBoolean) set_boolean_ = nullptr;
  decltype(&fmi2GetString) get_string_ = nullptr;
  decltype(&fmi2SetString) set_string_ = nullptr;
  decltype(&fmi2DoStep) do_step_ = nullptr;
  decltype(&fmi2GetRealStatus) get_real_status_ = nullptr;
  decltype(&fmi2GetBooleanStatus) get_boolean_status_ = nullptr;
};

/// PEP 440: the release, and the commit as a local version label.
std::string python_version() {
  const std::string commit = tirefe::kGitCommit;
  return std::string(tirefe::kVersion) + (commit.empty() || commit == "unknown" ? "" : "+g" + commit);
}

}  // namespace

PYBIND11_MODULE(_core, module) {
  module.doc() = "The compiled part of tirefe (import tirefe instead).";
  module.attr("__version__") = python_version();
  static py::exception<std::runtime_error> step_failed(module, "StepFailed", PyExc_RuntimeError);
  step_failed.doc() = "A step the tire could not solve; the tire stays at its committed state.";
  step_failed_type = step_failed.ptr();
  static py::exception<std::runtime_error> model_error(module, "ModelError", PyExc_RuntimeError);
  model_error.doc() = "A tire that cannot be built: a bad parameter value or file, named in the message.";
  model_error_type = model_error.ptr();

  module.def("run_deck", &run_deck, py::arg("deck"), py::arg("parameters") = std::map<std::string, py::object>{},
             py::arg("output_dir") = "results",
             R"(Runs a deck in this process as `tirefe DECK key=value ... --output-dir DIR --quiet` does.

parameters: overrides of the deck's tirefe.parameters{...} by name.
Returns {"status": the exit status of `tirefe` (0 success, 1 deck error, 2 usage, 3 a failed
self-check), "error": its error text, "files": the result files (.h5) the run wrote}.
Ctrl-C stops the run after its step, its files closed, and raises KeyboardInterrupt.)");

  module.def("static_forces", &static_forces, py::arg("source"), py::arg("parameters"), py::arg("deflections"),
             R"(The tire's static vertical curve on a flat frictionless road.

source: a tire property file (.tir) or a shipped parameter module ("tires.145SR12");
parameters: overrides by name; deflections: spindle deflections below first touch [m],
pressed in this order. Returns Fz [N] the tire exerts on the wheel at each (positive when
pressed), a numpy array. Ctrl-C stops it between presses (KeyboardInterrupt).)");

  py::class_<Tire>(module, "Tire", R"(A tire on a road driven through its spindle (the C API's tirefe_open).

ISO 8855 wheel axes (x the heading, z up, y the spin axis): motions (x, z, spin) [m, m, rad],
forces (Fx, Fz, My) [N, N, N m] the tire exerts on the wheel (a loaded tire: Fz > 0).
Usable as a context manager; close() frees it.)")
      .def(py::init<const std::string&, const std::map<std::string, double>&, double, double, bool, const std::string&,
                    const std::optional<std::string>&, const std::optional<std::string>&, double, double, double,
                    double, int, double, double, const std::optional<std::string>&, double>(),
           py::arg("source") = "tires.145SR12", py::arg("parameters") = std::map<std::string, double>{},
           py::arg("friction") = 0.8, py::arg("hht_alpha") = 0.0, py::arg("free_spin") = true,
           py::arg("heading") = "+x", py::arg("road") = py::none(), py::arg("road_track") = py::none(),
           py::arg("road_lateral") = 0.0, py::arg("road_start") = 0.0, py::arg("road_edge_radius") = 0.0,
           py::arg("start_z") = 0.0, py::arg("max_iterations") = 0, py::arg("max_time") = 0.0,
           py::arg("max_residual") = 0.0, py::arg("integrator") = py::none(), py::arg("rho_inf") = 0.9,
           R"(Builds, inflates and puts the tire on its road.

source: a tire property file (.tir) or a shipped parameter module; parameters: overrides by
name (keys of model:tire); friction: Coulomb coefficient; hht_alpha: 0 Newmark, [-1/3, 0)
HHT; free_spin: the wheel turns freely (My = 0) or the spin is given; heading: "+x" or "-x";
road: None (flat) or a road file (.rdf, .csv, or an ASCII OpenCRG road .crg), its x (an
OpenCRG road's u) along the heading from road_start and its height 0 where the tire touches
at z = 0, road_track "left" or "right" for a .rdf or .csv file with two, road_lateral [m]
the track of a .crg road (its lateral offset from the reference line, left positive; 0: the
reference line), its convex corners rounded by road_edge_radius [m]; start_z: the spindle's height [m]
when handed over (pressed quasi-statically from touching); max_iterations, max_time [s],
max_residual: a step budget for real time (tirefe_set_step_budget; 0: none, max_residual
1e-4): Newton ends after that many iterations or that much wall time at a relative residual
within max_residual, the step taken unconverged and counted (budget_report); a budget starts
every step from the zero-acceleration predictor.
integrator: None (hht_alpha decides) or a scheme by name, "newmark", "hht", "wbz" or
"generalized_alpha" (the last two with rho_inf in [0, 1]).
Raises ModelError for a tire that cannot be built, ValueError for bad arguments.)")
      .def("solve", method(&Tire::solve), py::arg("time_step"), py::arg("x"), py::arg("z"), py::arg("spin") = 0.0,
           R"(Solves the trial step of time_step [s] to the wheel centre's position (x, z, spin).

Returns (force, jacobian): force = (Fx, Fz, My), jacobian[i, j] = d force_i / d (x, z, spin)_j.
Raises StepFailed when it does not converge (the tire stays at its committed state).)")
      .def("solve_velocity", method(&Tire::solve_velocity), py::arg("time_step"), py::arg("vx"), py::arg("vz"),
           py::arg("spin_rate") = 0.0,
           R"(Solves the trial step to the end-of-step velocities (vx, vz, spin rate).

Returns (force, jacobian) with jacobian[i, j] = d force_i / d (vx, vz, spin rate)_j.)")
      .def("advance", method(&Tire::advance), py::arg("duration"), py::arg("start_velocity"), py::arg("position"),
           py::arg("velocity"), py::arg("max_step"),
           R"(Advances the tire by duration [s] in committed steps of its own of at most max_step.

The spindle moves from its committed position with the rates start_velocity (those the
path before ended with) to position (x, z, spin) with velocity at the end, along the cubic
that meets both ends; steps that do not converge are halved and grow back. Returns {"time", "steps", "cuts", "newton_iterations"}.
Raises StepFailed when a step fails even at its smallest: the tire stays at the last step
it committed.)")
      .def("budget_report", method(&Tire::budget_report),
           R"(The committed steps as the step budget saw them: {"steps", "unconverged" (ended by the
budget), "worst_residual" (their largest |R|/R_ref), "overruns" (more than max_iterations),
"time_misses" (over max_time), "worst_time" [s]}.)")
      .def("commit", method(&Tire::commit), "Accepts the last trial step: the tire advances to it.")
      .def("revert", method(&Tire::revert), "Forgets the last trial step.")
      .def("state", method(&Tire::state),
           R"(The committed state: {"time" [s], "position" (x, z, spin), "velocity", "force" (Fx, Fz, My)}.)")
      .def("road_level", method(&Tire::road_level), "Height of the road below the spindle's design position [m].")
      .def("close", method(&Tire::close), "Frees the tire; later calls raise ValueError.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](Tire* self, py::args) { method (&Tire::close)(self); });

  py::class_<FmiInstance>(module, "FmiInstance",
                          "The FMI 2.0 co-simulation calls of one instance of an FMU binary (tirefe.Fmu uses it).")
      .def(py::init<const std::string&, const std::string&, const std::string&, const std::string&, bool>(),
           py::arg("binary"), py::arg("guid"), py::arg("resource_uri"), py::arg("name"), py::arg("logging"))
      .def("setup_experiment", method(&FmiInstance::setup_experiment), py::arg("start"), py::arg("stop") = py::none())
      .def("enter_initialization_mode", method(&FmiInstance::enter_initialization_mode))
      .def("exit_initialization_mode", method(&FmiInstance::exit_initialization_mode))
      .def("terminate", method(&FmiInstance::terminate))
      .def("reset", method(&FmiInstance::reset))
      .def("free", method(&FmiInstance::free_instance))
      .def("do_step", method(&FmiInstance::do_step), py::arg("time"), py::arg("step"))
      .def("set_real", method(&FmiInstance::set_real))
      .def("set_integer", method(&FmiInstance::set_integer))
      .def("set_boolean", method(&FmiInstance::set_boolean))
      .def("set_string", method(&FmiInstance::set_string))
      .def("get_real", method(&FmiInstance::get_real))
      .def("get_integer", method(&FmiInstance::get_integer))
      .def("get_boolean", method(&FmiInstance::get_boolean))
      .def("get_string", method(&FmiInstance::get_string))
      .def("last_successful_time", method(&FmiInstance::last_successful_time))
      .def("terminated", method(&FmiInstance::terminated))
      .def("take_messages", method(&FmiInstance::take_messages));
}
