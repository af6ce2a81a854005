// Fitting macros: tirefe.fit{...} fits parameters of a deck's model function to measured
// data (the library is src/fitting/, the user guide docs/fitting.md), and
// tirefe.read_csv{...} reads a measured curve.
//
// The model function is Lua: model(p, columns) gets the parameter values by name (and the
// data file's columns, if any) and returns the list of predictions matching the data. It
// runs in protected mode: an error raised in it (a simulation that did not converge, say)
// marks that evaluation as failed and the optimiser steps back; at the initial parameters
// it ends the fit with a deck error, as does a stop asked for by SIGINT or SIGTERM.
// Unreachable models are collected before and after every call, so the result files they
// opened are closed before the next call reopens them.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numeric>
#include <optional>

#include "fitting/curve_data.hpp"
#include "fitting/fit_problem.hpp"
#include "io/fit_file.hpp"
#include "deck/deck_session.hpp"
#include "deck/interrupt.hpp"
#include "macros/macro_table.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

const MacroSpec& parameter_entry_spec() {
  static const MacroSpec spec{"fit.parameters",
                              "",
                              {{"name", VT::String, true, "", "parameter name"},
                               {"initial", VT::Number, true, "", "starting value"},
                               {"lower", VT::Number, false, "", "lower bound"},
                               {"upper", VT::Number, false, "", "upper bound"},
                               {"log", VT::Boolean, false, "", "search ln(value)", std::string("false")}},
                              ""};
  return spec;
}

std::vector<fitting::FitParameter> read_parameters(lua_State* L, const MacroArguments& arguments) {
  arguments.push_value("parameters");
  const int list = lua_gettop(L);
  const auto count = static_cast<lua_Integer>(lua_rawlen(L, list));
  if (count == 0) throw std::invalid_argument("'parameters' must list at least one {name = ..., initial = ...}");
  std::vector<fitting::FitParameter> parameters;
  for (lua_Integer i = 1; i <= count; ++i) {
    lua_rawgeti(L, list, i);
    if (!lua_istable(L, -1))
      throw std::invalid_argument("'parameters' entry " + std::to_string(i) +
                                  " must be a table {name = ..., initial = ...}");
    const MacroArguments entry(L, -1, parameter_entry_spec());  // raises a deck error on a bad entry
    fitting::FitParameter parameter;
    parameter.name = entry.string("name");
    parameter.initial = entry.number("initial");
    parameter.lower = entry.number_or("lower", -kInfinity);
    parameter.upper = entry.number_or("upper", kInfinity);
    parameter.log = entry.boolean("log");
    parameters.push_back(parameter);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return parameters;
}

/// Pushes {name = {values...}, ...} with every column in SI.
void push_columns(lua_State* L, const std::vector<fitting::DataColumn>& columns) {
  lua_createtable(L, 0, static_cast<int>(columns.size()));
  for (const auto& column : columns) {
    lua_createtable(L, static_cast<int>(column.values.size()), 0);
    for (size_t i = 0; i < column.values.size(); ++i) {
      lua_pushnumber(L, column.values[i]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, column.name.c_str());
  }
}

std::string axis_label(const fitting::DataColumn& column) {
  return column.si_unit.empty() ? column.name : column.name + " [" + column.si_unit + "]";
}

/// The SI value of one unit of the column as written in its file (1 without a unit).
double file_unit_to_si(const fitting::DataColumn& column) {
  for (const auto& suffix : fitting::unit_suffixes())
    if (column.unit == suffix.suffix) return suffix.to_si;
  return 1.0;
}

/// The file's columns on 'points' abscissae evenly spaced over the range of column
/// 'x': x itself, the others interpolated linearly between the data points.
std::vector<fitting::DataColumn> columns_on_grid(const std::vector<fitting::DataColumn>& columns, size_t x,
                                                 long long points) {
  const std::vector<double>& abscissa = columns[x].values;
  std::vector<size_t> order(abscissa.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return abscissa[a] < abscissa[b]; });
  const double first = abscissa[order.front()], last = abscissa[order.back()];
  std::vector<fitting::DataColumn> grid = columns;
  for (auto& column : grid) column.values.assign(static_cast<size_t>(points), 0.0);
  for (long long k = 0; k < points; ++k) {
    const double at = first + (last - first) * static_cast<double>(k) / static_cast<double>(points - 1);
    size_t i = 0;  // the sorted interval [i, i + 1] holding 'at'
    while (i + 2 < order.size() && abscissa[order[i + 1]] < at) ++i;
    const double a = abscissa[order[i]], b = abscissa[order[i + 1]];
    const double weight = b > a ? std::clamp((at - a) / (b - a), 0.0, 1.0) : 0.0;
    for (size_t c = 0; c < columns.size(); ++c) {
      const std::vector<double>& values = columns[c].values;
      grid[c].values[static_cast<size_t>(k)] =
          c == x ? at : values[order[i]] + weight * (values[order[i + 1]] - values[order[i]]);
    }
  }
  return grid;
}

/// A registry reference released when the macro returns, also on an error.
class RegistryReference {
 public:
  explicit RegistryReference(lua_State* L) : L_(L), reference_(luaL_ref(L, LUA_REGISTRYINDEX)) {}  // pops the value
  RegistryReference(const RegistryReference&) = delete;
  RegistryReference& operator=(const RegistryReference&) = delete;
  ~RegistryReference() { luaL_unref(L_, LUA_REGISTRYINDEX, reference_); }
  void push() const { lua_rawgeti(L_, LUA_REGISTRYINDEX, reference_); }

 private:
  lua_State* L_;
  int reference_;
};

/// The Lua model function seen as a fitting::PredictionModel.
fitting::PredictionModel lua_model(lua_State* L, const RegistryReference& function, const RegistryReference& columns,
                                   const std::vector<fitting::FitParameter>& parameters) {
  return [L, &function, &columns, &parameters](const Eigen::VectorXd& values) {
    lua_gc(L, LUA_GCCOLLECT);  // models the deck built before the fit may hold the same files
    function.push();
    lua_createtable(L, 0, static_cast<int>(parameters.size()));
    for (size_t j = 0; j < parameters.size(); ++j) {
      lua_pushnumber(L, values[static_cast<Eigen::Index>(j)]);
      lua_setfield(L, -2, parameters[j].name.c_str());
    }
    columns.push();
    const int status = lua_pcall(L, 2, 1, 0);
    const bool failed = status != LUA_OK;
    // Close what the call built (models and their result files) before the next call.
    struct Collect {
      lua_State* L;
      ~Collect() { lua_gc(L, LUA_GCCOLLECT); }
    } collect{L};
    if (failed) {
      const std::string message = error_text(L, -1);
      lua_pop(L, 1);
      // A run asked to stop (SIGINT, SIGTERM) stops the fit too, not just this evaluation.
      if (stop_signal().load()) throw std::runtime_error(message);
      // So does a deck out of Lua memory.
      const LuaSandbox* sandbox = LuaSandbox::from(L);
      if (sandbox && (status == LUA_ERRMEM || sandbox->memory_exceeded()))
        throw std::runtime_error(sandbox->memory_message());
      throw fitting::EvaluationError(message);
    }
    if (!lua_istable(L, -1)) {
      const std::string type = luaL_typename(L, -1);
      lua_pop(L, 1);
      throw std::invalid_argument("the model function must return a list of predictions, got a " + type);
    }
    Eigen::VectorXd predictions(static_cast<Eigen::Index>(lua_rawlen(L, -1)));
    for (Eigen::Index i = 0; i < predictions.size(); ++i) {
      const bool number = lua_rawgeti(L, -1, static_cast<lua_Integer>(i + 1)) == LUA_TNUMBER;
      predictions[i] = lua_tonumber(L, -1);
      lua_pop(L, 1);
      if (!number) {
        lua_pop(L, 1);
        throw std::invalid_argument("entry " + std::to_string(i + 1) +
                                    " of the model function's result is not a number");
      }
    }
    lua_pop(L, 1);
    return predictions;
  };
}

fitting::FitOptions fit_options(const MacroArguments& arguments, DeckSession& session) {
  fitting::FitOptions options;
  if (arguments.has("method"))
    options.method =
        arguments.string("method") == "brent" ? fitting::FitMethod::Brent : fitting::FitMethod::LevenbergMarquardt;
  options.tolerance = arguments.number("tolerance");
  options.max_evaluations = static_cast<int>(arguments.integer("max_evaluations"));
  options.differences = arguments.string("differences") == "central" ? fitting::FiniteDifference::Central
                                                                     : fitting::FiniteDifference::Forward;
  options.relative_step = arguments.number("relative_step");
  options.log = !session.quiet && arguments.boolean("log") ? &session.progress.output() : nullptr;
  return options;
}

Eigen::VectorXd to_eigen(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

void push_named(lua_State* L, const std::vector<fitting::FitParameter>& parameters, const Eigen::VectorXd& values) {
  lua_createtable(L, 0, static_cast<int>(parameters.size()));
  for (size_t j = 0; j < parameters.size(); ++j) {
    const double value = values[static_cast<Eigen::Index>(j)];
    if (std::isnan(value)) continue;  // not identifiable or not available: absent, not a number to use
    lua_pushnumber(L, value);
    lua_setfield(L, -2, parameters[j].name.c_str());
  }
}

void push_list(lua_State* L, const Eigen::VectorXd& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void push_result(lua_State* L, const fitting::FitResult& result, const std::vector<fitting::FitParameter>& parameters) {
  lua_createtable(L, 0, 12);
  push_named(L, parameters, result.values);
  lua_setfield(L, -2, "values");
  push_named(L, parameters, result.standard_errors);
  lua_setfield(L, -2, "standard_errors");
  lua_createtable(L, static_cast<int>(parameters.size()), 0);
  for (Eigen::Index i = 0; i < result.correlation.rows(); ++i) {
    push_list(L, result.correlation.row(i).transpose());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "correlation");
  push_list(L, result.prediction);
  lua_setfield(L, -2, "prediction");
  lua_createtable(L, static_cast<int>(result.not_identifiable.size()), 0);
  for (size_t i = 0; i < result.not_identifiable.size(); ++i) {
    lua_pushstring(L, result.not_identifiable[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "not_identifiable");
  lua_pushstring(L, fitting::status_name(result.status));
  lua_setfield(L, -2, "status");
  lua_pushstring(L, result.message.c_str());
  lua_setfield(L, -2, "message");
  lua_pushstring(L, result.method.c_str());
  lua_setfield(L, -2, "method");
  lua_pushnumber(L, result.objective);
  lua_setfield(L, -2, "objective");
  lua_pushinteger(L, result.evaluations);
  lua_setfield(L, -2, "evaluations");
  lua_pushinteger(L, result.iterations);
  lua_setfield(L, -2, "iterations");
}

int fit_macro(lua_State* L, DeckSession& session, const MacroArguments& arguments) {
  fitting::FitProblem problem;
  problem.parameters = read_parameters(L, arguments);
  if (arguments.has("data") == arguments.has("data_file"))
    throw std::invalid_argument("give either 'data' or 'data_file'");
  if (arguments.has("data") && arguments.has("data_column"))
    throw std::invalid_argument("'data_column' goes with 'data_file', not with 'data'");
  if (arguments.has("data_file") && arguments.has("x"))
    throw std::invalid_argument("'x' goes with 'data'; with 'data_file' the file's first other column is the abscissa");

  const long long curve_points = arguments.integer("curve_points");
  if (curve_points > 10000)
    throw std::invalid_argument("'curve_points' = " + std::to_string(curve_points) +
                                " is more than a plot needs "
                                "(at most 10000)");
  io::FitAxes axes;
  std::optional<fitting::CurveData> curve;  // the data file
  size_t x_column = 0;
  if (arguments.has("data")) {
    problem.data = to_eigen(arguments.number_list("data"));
    if (arguments.has("x")) axes.x = to_eigen(arguments.number_list("x"));
    lua_pushnil(L);  // no columns for the model function
  } else {
    if (!arguments.has("data_column"))
      throw std::invalid_argument("'data_file' needs 'data_column' (the measured column)");
    curve = fitting::CurveData::read_csv(deck_relative(session, arguments.string("data_file")));
    const fitting::DataColumn& measured = curve->column(arguments.string("data_column"));
    problem.data = to_eigen(measured.values);
    axes.data_label = axis_label(measured);
    axes.data_unit = measured.unit;
    axes.data_to_si = file_unit_to_si(measured);
    for (size_t c = 0; c < curve->columns().size(); ++c) {
      const fitting::DataColumn& column = curve->columns()[c];
      if (&column != &measured && axes.x.size() == 0) {
        axes.x = to_eigen(column.values);
        axes.x_label = axis_label(column);
        axes.x_unit = column.unit;
        axes.x_to_si = file_unit_to_si(column);
        x_column = c;
      }
    }
    push_columns(L, curve->columns());
  }
  const RegistryReference columns(L);
  if (axes.x.size() && axes.x.size() != problem.data.size())
    throw std::invalid_argument("'x' has " + std::to_string(axes.x.size()) + " values for " +
                                std::to_string(problem.data.size()) + " data points");
  if (arguments.has("weights")) problem.weights = to_eigen(arguments.number_list("weights"));

  arguments.push_value("model");
  const RegistryReference function(L);
  problem.model = lua_model(L, function, columns, problem.parameters);
  // Checked before the fit's work, which a refused name would waste.
  const std::string output = arguments.has("output") ? deck_output_path(session, arguments.string("output"),
                                                                        OutputFile::hdf5("a fit result file"))
                                                     : "";
  const fitting::FitResult result = fitting::fit(problem, fit_options(arguments, session));

  if (!output.empty() && curve && axes.x.size() > 1 && curve_points >= 2 && result.values.allFinite()) {
    // The fitted model between the data points, for the plot: one more evaluation with
    // the data file's columns on a fine grid. A model that cannot take them (it fails, or
    // returns as many values as there are data points) is drawn at the data points only.
    const std::vector<fitting::DataColumn> grid = columns_on_grid(curve->columns(), x_column, curve_points);
    push_columns(L, grid);
    const RegistryReference grid_columns(L);
    try {
      const Eigen::VectorXd on_grid = lua_model(L, function, grid_columns, problem.parameters)(result.values);
      if (on_grid.size() == curve_points) {
        axes.curve_x = to_eigen(grid[x_column].values);
        axes.curve_prediction = on_grid;
      }
    } catch (const fitting::EvaluationError&) {  // the model failed on the grid: no curve
    } catch (const std::invalid_argument&) {     // it returned something else than numbers: no curve
    }
  }
  if (!output.empty()) io::write_fit_file(output, problem, result, axes, session.deck_path);
  push_result(L, result, problem.parameters);
  return 1;
}

int read_csv_macro(lua_State* L, DeckSession& session, const MacroArguments& arguments) {
  push_columns(L, fitting::CurveData::read_csv(deck_relative(session, arguments.string("file"))).columns());
  return 1;
}

}  // namespace

void add_fitting_macros(MacroTable& table) {
  table.module_macros.push_back(
      {{"fit",
        "Fits parameters of a model function to measured data by weighted least squares (docs/fitting.md): "
        "Brent's method for one parameter, Levenberg-Marquardt for several. model(p, columns) receives the "
        "parameter values by name (p.k_sw) and the data file's columns (in SI, or nil), and returns a list of "
        "predictions matching the data; an error raised in it marks that evaluation as failed. Each entry of "
        "'parameters' is {name = ..., initial = ..., lower = ..., upper = ..., log = true/false}; log searches "
        "ln(value) (relative steps; for positive parameters such as stiffnesses). Returns {values, "
        "standard_errors, correlation, prediction, status, message, not_identifiable, method, objective, "
        "evaluations, iterations}; status is converged, at_bound, not_identifiable or max_evaluations, and "
        "values holds no entry for a parameter the data cannot determine.",
        {{"parameters", VT::Table, true, "", "list of {name, initial, lower, upper, log}"},
         {"model", VT::Function, true, "", "function(p, columns) returning the list of predictions"},
         {"data", VT::NumberList, false, "", "measured values (instead of data_file)"},
         {"data_file", VT::String, false, "",
          "CSV file with a header of column names with unit suffixes (deflection_mm, force_N), relative to the "
          "deck's folder"},
         {"data_column", VT::String, false, "", "the column of data_file holding the measured values"},
         {"x", VT::NumberList, false, "",
          "abscissa of the data points, for the plot (data_file: its first other "
          "column)"},
         {"weights", VT::NumberList, false, "", "relative weight of each data point (default 1)", std::nullopt,
          Range::Positive},
         {"method",
          VT::String,
          false,
          "",
          "default: brent for one parameter, else levenberg_marquardt",
          std::nullopt,
          Range::Any,
          {"brent", "levenberg_marquardt"}},
         {"tolerance", VT::Number, false, "", "stop when every parameter changes by less than this fraction",
          std::string("1e-6"), Range::Positive},
         {"max_evaluations", VT::Integer, false, "", "model evaluations before giving up", std::string("100"),
          Range::Positive},
         {"differences",
          VT::String,
          false,
          "",
          "finite-difference derivatives",
          std::string("forward"),
          Range::Any,
          {"forward", "central"}},
         {"relative_step", VT::Number, false, "", "finite-difference step relative to the parameter",
          std::string("1e-6"), Range::Positive},
         {"log", VT::Boolean, false, "", "print every iteration", std::string("true")},
         {"output", VT::String, false, "", "HDF5 file for the history, data and prediction (in the output folder)"},
         {"curve_points", VT::Integer, false, "",
          "with data_file and output: the model at the fitted values on this many points evenly spread over the "
          "abscissa's range (one more evaluation, the other columns interpolated), for a continuous curve in the "
          "plot; 0: none",
          std::string("0"), Range::NonNegative}},
        "local fit = tirefe.fit{\n"
        "  parameters = { { name = \"k_sw\", initial = 80, lower = 1, upper = 1000, log = true } },\n"
        "  data_file = \"vertical_208kPa.csv\", data_column = \"force\",\n"
        "  model = function(p, curve) return flat_road_forces(p.k_sw, curve.deflection) end,\n"
        "  output = \"k_sw_fit.h5\" }\n"
        "print(fit.status, fit.values.k_sw, fit.standard_errors.k_sw)"},
       fit_macro});
  table.module_macros.push_back(
      {{"read_csv",
        "Reads a measured curve from a CSV file (docs/fitting.md): returns a table of columns by name, each "
        "converted to SI from the header's unit suffix (deflection_mm -> deflection in m).",
        {{"file", VT::String, true, "", "CSV file, relative to the deck's folder"}},
        "local curve = tirefe.read_csv{ file = \"vertical_150kPa.csv\" }\nprint(#curve.deflection, curve.force[1])"},
       read_csv_macro});
}

}  // namespace tirefe::macros
