// Tests of parameter fitting (src/fitting/, the tirefe.fit macro): Brent's method on
// analytic functions, Levenberg-Marquardt on a nonlinear force-deflection law from exact
// and noisy data (standard errors against a Monte-Carlo estimate), identifiability
// reports, the CSV reader, and the macro end to end in the deck sandbox.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "fitting/brent.hpp"
#include "fitting/curve_data.hpp"
#include "fitting/fit_problem.hpp"
#include "io/hdf5_file.hpp"
#include "deck/deck_session.hpp"
#include "deck/lua_sandbox.hpp"
#include "macros/macro_table.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe::fitting;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using tirefe::testing::TempDir;

double relative_error(double value, double expected) { return std::abs(value - expected) / std::abs(expected); }

ScalarSearch scalar_search(std::function<double(double)> f, double tolerance, int* calls = nullptr) {
  ScalarSearch search;
  search.function = [f, calls](double x) {
    if (calls) ++*calls;
    return f(x);
  };
  search.tolerance = [tolerance](double x) { return tolerance * std::max(std::abs(x), 1.0); };
  return search;
}

// Deflections 2..30 mm of a force-deflection test.
Eigen::VectorXd deflections() { return Eigen::VectorXd::LinSpaced(15, 0.002, 0.030); }

// A softening force-deflection law: F = a (1 - exp(-d / c)) + b d.
Eigen::VectorXd softening_force(const Eigen::VectorXd& p, const Eigen::VectorXd& d) {
  return p[0] * (1.0 - (-d.array() / p[1]).exp()) + p[2] * d.array();
}
const Eigen::Vector3d kTrueSoftening(2000.0, 0.01, 1.2e5);  // a [N], c [m], b [N/m]

FitProblem softening_problem(const Eigen::VectorXd& data, bool log) {
  FitProblem problem;
  problem.parameters = {{"a", 1000.0, 1.0, 1e5, log}, {"c", 0.02, 1e-4, 1.0, log}, {"b", 5e4, 1.0, 1e7, log}};
  problem.model = [](const Eigen::VectorXd& p) { return softening_force(p, deflections()); };
  problem.data = data;
  return problem;
}

// Measured forces with 2 % relative noise, weighted as relative errors (w = 1 / y^2).
FitProblem noisy_softening_problem(unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  Eigen::VectorXd data = softening_force(kTrueSoftening, deflections());
  for (Eigen::Index i = 0; i < data.size(); ++i) data[i] *= 1.0 + noise(random);
  FitProblem problem = softening_problem(data, true);
  problem.weights = data.cwiseAbs2().cwiseInverse();
  return problem;
}

// F = k d^1.5 (a Hertz-like contact law): one stiffness to fit.
FitProblem stiffness_problem(double initial, std::vector<double>* evaluated = nullptr) {
  FitProblem problem;
  problem.parameters = {{"k", initial, 1.0, 1e9, true}};
  const Eigen::VectorXd d = deflections();
  problem.model = [d, evaluated](const Eigen::VectorXd& p) {
    if (evaluated) evaluated->push_back(p[0]);
    return Eigen::VectorXd(p[0] * d.array().pow(1.5));
  };
  problem.data = 2.5e6 * d.array().pow(1.5);
  return problem;
}

// Runs a deck in the sandbox with the macros installed, as the tirefe binary does.
struct DeckRun {
  tirefe::macros::DeckSession session;
  tirefe::macros::LuaSandbox sandbox{TIREFE_LUA_DIR};

  explicit DeckRun(const std::string& output_dir) {
    session.output_dir = output_dir;
    session.quiet = true;
    tirefe::macros::install_macros(sandbox, session);
  }
  void run(const std::string& deck) {
    session.deck_path = deck;
    sandbox.run_file(deck);
  }
  // A number in the deck's global table 'name' at 'path' (e.g. {"values", "k"}).
  double number(const char* name, std::vector<const char*> path) {
    lua_State* L = sandbox.state();
    lua_getglobal(L, name);
    for (const char* key : path) lua_getfield(L, -1, key);
    const double value = lua_isnumber(L, -1) ? lua_tonumber(L, -1) : std::nan("");
    lua_pop(L, static_cast<int>(path.size()) + 1);
    return value;
  }
  std::string text(const char* name, const char* key) {
    lua_State* L = sandbox.state();
    lua_getglobal(L, name);
    lua_getfield(L, -1, key);
    const std::string value = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
    lua_pop(L, 2);
    return value;
  }
};

}  // namespace

TEST_CASE("Brent's method finds the minima of analytic functions to 1e-8 in few evaluations", "[fitting]") {
  struct Case {
    const char* name;
    std::function<double(double)> f;
    double x0, step, minimum;
    int max_calls;
  };
  const std::vector<Case> cases{
      {"quadratic (x - 2)^2", [](double x) { return (x - 2.0) * (x - 2.0); }, 0.0, 0.5, 2.0, 12},
      {"(exp x - 3)^2", [](double x) { return std::pow(std::exp(x) - 3.0, 2); }, 0.0, 0.1, std::log(3.0), 20},
      {"log(1 + (x - 1.5)^2)", [](double x) { return std::log1p((x - 1.5) * (x - 1.5)); }, 5.0, -1.0, 1.5, 20},
      {"(x^2 - 2)^2 + (x^2 - 2)^4", [](double x) { return std::pow(x * x - 2, 2) + std::pow(x * x - 2, 4); }, 3.0, -0.2,
       std::sqrt(2.0), 20}};
  for (const Case& c : cases) {
    INFO(c.name);
    int calls = 0;
    const ScalarMinimum minimum = minimize_scalar(scalar_search(c.f, 1e-8, &calls), c.x0, c.step);
    CHECK(minimum.outcome == ScalarMinimum::Outcome::Converged);
    CHECK(std::abs(minimum.x - c.minimum) <= 1e-8 * std::abs(c.minimum));
    CHECK(minimum.evaluations == calls);
    CHECK(calls <= c.max_calls);
  }
}

TEST_CASE("Brent's method: a minimum with a non-zero value is found to its resolution", "[fitting]") {
  // f = x - ln x has f(1) = 1: near the minimum f changes by (x-1)^2/2, so x is resolved
  // only to about sqrt(2 eps) ~ 2e-8.
  int calls = 0;
  const ScalarMinimum minimum =
      minimize_scalar(scalar_search([](double x) { return x - std::log(x); }, 1e-6, &calls), 3.0, -0.5);
  CHECK(minimum.outcome == ScalarMinimum::Outcome::Converged);
  CHECK(std::abs(minimum.x - 1.0) <= 1e-6);
  CHECK(calls <= 20);
}

TEST_CASE("Brent's method respects the bounds and reports a minimum on a bound", "[fitting]") {
  std::vector<double> evaluated;
  ScalarSearch search = scalar_search(
      [&](double x) {
        evaluated.push_back(x);
        return (x - 5.0) * (x - 5.0);
      },
      1e-8);
  search.lower = -1.0;
  search.upper = 3.0;
  const ScalarMinimum minimum = minimize_scalar(search, 0.0, 1.0);
  CHECK(minimum.outcome == ScalarMinimum::Outcome::AtBound);
  CHECK(minimum.x == 3.0);
  for (double x : evaluated) CHECK((x >= -1.0 && x <= 3.0));

  SECTION("and stops when the evaluation budget is spent") {
    search.max_evaluations = 3;
    search.upper = 10.0;
    evaluated.clear();
    const ScalarMinimum stopped = minimize_scalar(search, 0.0, 0.1);
    CHECK(stopped.outcome == ScalarMinimum::Outcome::MaxEvaluations);
    CHECK(evaluated.size() == 3);
    CHECK(stopped.x == evaluated.back());  // the best of 0, 0.1, 0.11 is the last
  }
}

TEST_CASE("a one-parameter fit (Brent, log parameter) recovers a stiffness from exact data", "[fitting]") {
  std::vector<double> evaluated;
  FitProblem problem = stiffness_problem(2e5, &evaluated);  // a factor 12.5 below the truth
  std::ostringstream log;
  FitOptions options;
  options.tolerance = 1e-8;
  options.log = &log;
  const FitResult result = fit(problem, options);
  INFO(log.str());
  CHECK(result.method == "brent");
  CHECK(result.status == FitStatus::Converged);
  CHECK(relative_error(result.values[0], 2.5e6) <= 1e-8);
  CHECK(result.evaluations == static_cast<int>(evaluated.size()));
  CHECK(result.evaluations <= 16);
  for (double k : evaluated) CHECK((k >= 1.0 && k <= 1e9));
  // History: one row per iteration, objective never rising, the log prints each row.
  REQUIRE(result.history.size() >= 3);
  CHECK(result.history.front().values[0] == Approx(2e5).epsilon(1e-15));
  for (size_t i = 1; i < result.history.size(); ++i)
    CHECK(result.history[i].objective <= result.history[i - 1].objective);
  CHECK(result.history.back().evaluations <= result.evaluations);
  const std::string text = log.str();
  size_t lines = 0;
  for (size_t at = text.find("evaluations "); at != std::string::npos; at = text.find("evaluations ", at + 1)) ++lines;
  CHECK(lines == result.history.size());
  CHECK_THAT(text, Contains("converged after"));
}

TEST_CASE("a one-parameter fit steps back from evaluations that fail", "[fitting]") {
  FitProblem problem = stiffness_problem(1e6);
  const PredictionModel exact = problem.model;
  int failures = 0;
  problem.model = [&](const Eigen::VectorXd& p) {
    if (p[0] > 2.6e6) {  // just above the solution, a simulation that does not converge
      ++failures;
      throw EvaluationError("Newton iterations diverge");
    }
    return exact(p);
  };
  FitOptions options;
  options.tolerance = 1e-8;
  const FitResult result = fit(problem, options);
  CHECK(failures >= 1);
  CHECK(result.status == FitStatus::Converged);
  CHECK(relative_error(result.values[0], 2.5e6) <= 1e-8);

  SECTION("but a model failing at the initial parameters is an error") {
    problem.parameters[0].initial = 3e6;
    CHECK_THROWS_WITH(fit(problem, options),
                      Contains("initial parameters (k = 3000000)") && Contains("Newton iterations diverge"));
  }
}

TEST_CASE("Levenberg-Marquardt recovers a nonlinear force-deflection law from exact data to 1e-8", "[fitting]") {
  for (const bool log : {true, false}) {
    INFO("log parametrisation " << log);
    const FitProblem problem = softening_problem(softening_force(kTrueSoftening, deflections()), log);
    FitOptions options;
    options.tolerance = 1e-10;
    options.max_evaluations = 400;
    const FitResult result = fit(problem, options);
    INFO(result.message);
    CHECK(result.method == "levenberg_marquardt");
    CHECK(result.status == FitStatus::Converged);
    for (int j = 0; j < 3; ++j) CHECK(relative_error(result.values[j], kTrueSoftening[j]) <= 1e-8);
    CHECK(result.evaluations < 200);
  }
}

TEST_CASE("Levenberg-Marquardt with central differences and a quadratic law F = a d + b d^2", "[fitting]") {
  FitProblem problem;
  problem.parameters = {{"a", 1e4, -1e9, 1e9, false}, {"b", 0.0, -1e9, 1e9, false}};
  const Eigen::VectorXd d = deflections();
  problem.model = [d](const Eigen::VectorXd& p) {
    return Eigen::VectorXd(p[0] * d.array() + p[1] * d.array().square());
  };
  problem.data = 1.9e5 * d.array() + 2.0e6 * d.array().square();
  FitOptions options;
  options.differences = FiniteDifference::Central;
  options.tolerance = 1e-10;
  const FitResult result = fit(problem, options);
  CHECK(result.status == FitStatus::Converged);
  CHECK(relative_error(result.values[0], 1.9e5) <= 1e-8);
  CHECK(relative_error(result.values[1], 2.0e6) <= 1e-8);
}

TEST_CASE("from data with 2 % noise the estimate lies within 3 standard errors, which match Monte Carlo", "[fitting]") {
  FitOptions options;
  options.tolerance = 1e-9;
  options.max_evaluations = 400;
  const FitResult one = fit(noisy_softening_problem(1), options);
  REQUIRE(one.status == FitStatus::Converged);
  for (int j = 0; j < 3; ++j) {
    INFO("parameter " << j << ": " << one.values[j] << " +- " << one.standard_errors[j]);
    CHECK(std::isfinite(one.standard_errors[j]));
    CHECK(std::abs(one.values[j] - kTrueSoftening[j]) <= 3.0 * one.standard_errors[j]);
  }
  CHECK(one.correlation(0, 0) == Approx(1.0));
  CHECK(one.correlation(0, 1) == Approx(one.correlation(1, 0)));
  CHECK(std::abs(one.correlation(0, 2)) < 1.0);

  // 30 noise samples: the scatter of the estimates against the mean reported standard error.
  const int samples = 30;
  Eigen::MatrixXd estimates(samples, 3), errors(samples, 3);
  for (int s = 0; s < samples; ++s) {
    const FitResult result = fit(noisy_softening_problem(100 + s), options);
    REQUIRE(result.status == FitStatus::Converged);
    estimates.row(s) = result.values.transpose();
    errors.row(s) = result.standard_errors.transpose();
  }
  for (int j = 0; j < 3; ++j) {
    const Eigen::VectorXd centred = estimates.col(j).array() - estimates.col(j).mean();
    const double scatter = std::sqrt(centred.squaredNorm() / (samples - 1));
    const double reported = errors.col(j).mean();
    INFO("parameter " << j << ": Monte-Carlo scatter " << scatter << ", mean standard error " << reported);
    CHECK(reported / scatter >= 1.0 / 1.5);
    CHECK(reported / scatter <= 1.5);
  }
}

TEST_CASE("a parameter the model ignores is reported as not identifiable", "[fitting]") {
  FitProblem problem = softening_problem(softening_force(kTrueSoftening, deflections()), true);
  problem.parameters.push_back({"temperature", 20.0, -50.0, 150.0, false});
  int calls = 0;
  problem.model = [&](const Eigen::VectorXd& p) {
    ++calls;
    return softening_force(p.head(3), deflections());
  };
  const FitResult result = fit(problem);
  CHECK(result.status == FitStatus::NotIdentifiable);
  CHECK(result.not_identifiable == std::vector<std::string>{"temperature"});
  CHECK_THAT(result.message, Contains("insensitive to 'temperature'"));
  CHECK(result.values.array().isNaN().all());  // stopped before fitting anything
  CHECK(calls == 5);                           // the initial point and its Jacobian only

  SECTION("also by the one-parameter search") {
    FitProblem single = stiffness_problem(1e6);
    single.model = [](const Eigen::VectorXd&) { return Eigen::VectorXd(Eigen::VectorXd::Ones(15)); };
    const FitResult ignored = fit(single);
    CHECK(ignored.status == FitStatus::NotIdentifiable);
    CHECK(ignored.not_identifiable == std::vector<std::string>{"k"});
  }
}

TEST_CASE("parameters acting only as a product are reported as not identifiable", "[fitting]") {
  FitProblem problem;
  problem.parameters = {{"k_tread", 1.0, 0.01, 100.0, true}, {"k_sw", 2.0, 0.01, 100.0, true}};
  const Eigen::VectorXd d = deflections();
  problem.model = [d](const Eigen::VectorXd& p) { return Eigen::VectorXd(p[0] * p[1] * d); };
  problem.data = 3.0 * d;
  const FitResult result = fit(problem);
  CHECK(result.status == FitStatus::NotIdentifiable);
  CHECK(result.not_identifiable == std::vector<std::string>{"k_tread", "k_sw"});
  CHECK_THAT(result.message, Contains("'k_tread' and 'k_sw' cannot be told apart"));
  CHECK(result.condition_number > 1e10);
}

TEST_CASE("fewer data points than parameters is reported before any evaluation", "[fitting]") {
  FitProblem problem = softening_problem(Eigen::Vector2d(100.0, 200.0), true);
  int calls = 0;
  problem.model = [&](const Eigen::VectorXd&) {
    ++calls;
    return Eigen::VectorXd(Eigen::Vector2d(1.0, 2.0));
  };
  const FitResult result = fit(problem);
  CHECK(result.status == FitStatus::NotIdentifiable);
  CHECK_THAT(result.message, Contains("2 data points cannot determine 3 parameters"));
  CHECK(calls == 0);
  CHECK(result.evaluations == 0);
  CHECK(result.not_identifiable.size() == 3);
}

TEST_CASE("Levenberg-Marquardt holds a parameter the data push beyond its bound", "[fitting]") {
  FitProblem problem = softening_problem(softening_force(kTrueSoftening, deflections()), true);
  problem.parameters[2].upper = 1e5;  // the truth, b = 1.2e5, is outside
  FitOptions options;
  options.max_evaluations = 400;
  const FitResult result = fit(problem, options);
  CHECK(result.status == FitStatus::AtBound);
  CHECK_THAT(result.message, Contains("'b' (upper)"));
  CHECK(result.values[2] == Approx(1e5).epsilon(1e-12));
  CHECK(std::isnan(result.standard_errors[2]));
  CHECK(std::isfinite(result.standard_errors[0]));
}

TEST_CASE("inconsistent fit problems are refused with a clear message", "[fitting]") {
  FitProblem problem = stiffness_problem(1e6);
  problem.parameters[0].initial = 1e10;
  CHECK_THROWS_WITH(fit(problem), Contains("'k': the initial value 1e+10 is outside [1, 1e+09]"));
  problem = stiffness_problem(1e6);
  problem.model = [](const Eigen::VectorXd&) { return Eigen::VectorXd(Eigen::VectorXd::Ones(3)); };
  CHECK_THROWS_WITH(fit(problem), Contains("the model returned 3 predictions for 15 data points"));
  problem = stiffness_problem(1e6);
  FitOptions options;
  options.method = FitMethod::Brent;
  problem.parameters.push_back({"c", 1.0});
  CHECK_THROWS_WITH(fit(problem, options), Contains("Brent's method fits one parameter"));
}

TEST_CASE("the CSV reader converts unit suffixes to SI and names bad rows by file and line", "[fitting]") {
  TempDir folder;
  const std::string good = folder.write("curve.csv",
                                        "# vertical stiffness, flat road\n"
                                        "\n"
                                        "deflection_mm, force_kN, pressure_kPa, label\n"
                                        "5.0, 0.96, 208, 1   # first point\n"
                                        "10.0,2.05,208,2\n");
  const CurveData curve = CurveData::read_csv(good);
  CHECK(curve.rows() == 2);
  CHECK(curve.column("deflection").values[0] == Approx(0.005).epsilon(1e-15));
  CHECK(curve.column("deflection").values[1] == Approx(0.010).epsilon(1e-15));
  CHECK(curve.column("force_kN").values[1] == Approx(2050.0).epsilon(1e-15));
  CHECK(curve.column("pressure").values[0] == 208e3);
  CHECK(curve.column("pressure").si_unit == "Pa");
  CHECK(curve.column("label").values[1] == 2.0);  // no suffix: as written
  CHECK_THROWS_WITH(curve.column("force_N"), Contains("no column 'force_N' (columns: deflection_mm, force_kN"));

  const std::string bad_value = folder.write("bad_value.csv", "deflection_mm, force_N\n1, 10\n# note\n2, 2O\n");
  CHECK_THROWS_WITH(CurveData::read_csv(bad_value),
                    Contains(bad_value + ":4: column 'force_N': '2O' is not a finite number"));
  const std::string short_row = folder.write("short_row.csv", "deflection_mm, force_N\n1, 10\n2\n");
  CHECK_THROWS_WITH(CurveData::read_csv(short_row),
                    Contains(short_row + ":3: expected 2 values (deflection_mm, force_N), found 1"));
  CHECK_THROWS_WITH(CurveData::read_csv(folder.path("missing.csv")), Contains("cannot open"));
}

TEST_CASE("the CSV reader skips a byte order mark, refuses hex, NUL and overflow, reads underflow as 0", "[fitting]") {
  TempDir folder;
  const CurveData marked = CurveData::read_csv(folder.write("bom.csv",
                                                            "\xEF\xBB\xBF"
                                                            "deflection_mm, force_N\n1, 10\n"));
  CHECK(marked.columns().front().name == "deflection");
  CHECK(marked.column("deflection").values[0] == Approx(1e-3).epsilon(1e-15));

  const CurveData tiny = CurveData::read_csv(folder.write("tiny.csv", "x, y\n1e-400, -1e-400\n2.5e-310, 1\n"));
  CHECK(tiny.column("x").values[0] == 0.0);
  CHECK(tiny.column("y").values[0] == 0.0);
  CHECK(tiny.column("x").values[1] == Approx(2.5e-310).epsilon(1e-6));  // subnormal, kept

  // clang-format off
  const std::pair<std::string, std::string> refused[] = {
      {"hex.csv", "x, y\n0x10, 1\n"},          {"hex_float.csv", "x, y\n1, 0x1p3\n"},
      {"inf.csv", "x, y\ninf, 1\n"},           {"overflow.csv", "x, y\n1e400, 1\n"},
      {"nan.csv", "x, y\n1, nan\n"},           {"nul.csv", std::string("x, y\n1, 12", 10) + std::string("\0" "5\n", 3)}};
  // clang-format on
  for (const auto& [name, text] : refused) {
    INFO(name);
    CHECK_THROWS_WITH(CurveData::read_csv(folder.write(name, text)),
                      Contains(name + ":2: column") && Contains("is not a finite number"));
  }
  CHECK_THROWS_WITH(CurveData::read_csv(folder.write("nul_name.csv", std::string("x, y\0z\n1, 2\n", 12))),
                    Contains("nul_name.csv:1: column name 'y?z' holds a control character or NUL byte"));

  // 100 000 columns: the duplicate check is linear (it was quadratic: 33 s).
  std::string header, row;
  for (int c = 0; c < 100000; ++c) {
    header += (c ? ",c" : "c") + std::to_string(c);
    row += c ? ",1" : "1";
  }
  const auto started = std::chrono::steady_clock::now();
  const CurveData wide = CurveData::read_csv(folder.write("wide.csv", header + "\n" + row + "\n"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  CHECK(wide.columns().size() == 100000);
  // A complexity guard, not a speed claim: the quadratic check took 33 s, the linear one
  // takes a fraction of a second, so 15 s tells them apart on a loaded machine.
  CHECK(seconds < 15.0);
  CHECK_THROWS_WITH(CurveData::read_csv(folder.write("twice.csv", header + ",c99999\n" + row + ",1\n")),
                    Contains("two columns named 'c99999'"));
}

TEST_CASE("tirefe.fit works end to end in a deck: CSV data, a Lua model, the HDF5 output", "[fitting]") {
  TempDir folder;
  // Tip deflections of a 1 m cantilever under three small loads, from beam theory with
  // EI = 2.5 N m^2: P L^3 / (3 EI).
  folder.write("tip.csv",
               "# tip deflection of a 1 m cantilever, EI = 2.5 N m^2\n"
               "load_N, deflection_mm\n"
               "0.001, 0.13333333333333\n"
               "0.002, 0.26666666666667\n"
               "0.003, 0.4\n");
  const std::string deck = folder.write("fit_cantilever.lua", R"(
-- The model function builds and solves a small cantilever for each EI it is given.
local function tip_deflections(EI, loads)
  local model = tirefe.model{ title = "cantilever" }
  local nodes = {}
  for i = 0, 4 do nodes[#nodes + 1] = model:node{ x = i / 4, y = 0 } end
  model:section{ name = "beam", EA = 1e9, GA = 1e9, EI = EI }
  model:beam{ section = "beam", nodes = nodes }
  model:fix{ node = nodes[1] }
  model:load{ node = nodes[5], fy = -loads[#loads] }
  model:output{ file = "evaluation.h5" }
  local deflections = {}
  for i = 1, #loads do
    model:solve{ to = i / #loads, dt = 1 / #loads }
    deflections[i] = -model:value{ node = nodes[5], dof = "uy" }
  end
  return deflections
end

result = tirefe.fit{
  parameters = { { name = "EI", initial = 1.0, lower = 0.01, upper = 100, log = true } },
  data_file = "tip.csv", data_column = "deflection",
  model = function(p, columns) return tip_deflections(p.EI, columns.load) end,
  tolerance = 1e-7, output = "fit_EI.h5" }
third_deflection = tirefe.read_csv{ file = "tip.csv" }.deflection[3]
)");
  DeckRun run(folder.path("out"));
  run.run(deck);
  CHECK(run.text("result", "status") == "converged");
  CHECK(run.text("result", "method") == "brent");
  // N = 4 beam elements with one-point quadrature are too stiff in bending: their tip
  // deflection is P L^3 / (3 EI) (1 - 1 / (4 N^2)), so the fit finds the EI that makes them
  // match, 2.5 (1 - 1/64). Geometric nonlinearity at P L^2 / EI ~ 1e-3 is below 1e-6.
  CHECK(relative_error(run.number("result", {"values", "EI"}), 2.5 * (1.0 - 1.0 / 64.0)) <= 1e-6);
  CHECK(run.number("result", {"standard_errors", "EI"}) < 1e-4);
  CHECK(run.number("result", {"evaluations"}) <= 20);
  CHECK(run.number("third_deflection", {}) == Approx(0.0004).epsilon(1e-12));  // tirefe.read_csv, in m

  const auto file = tirefe::io::Hdf5File::open_read_only(folder.path("out/fit_EI.h5"));
  CHECK(file.read_string_attribute("/", "status") == "converged");
  CHECK(file.read_strings("/fit/parameters/name") == std::vector<std::string>{"EI"});
  const std::vector<double> data = file.read_doubles("/fit/data"), prediction = file.read_doubles("/fit/prediction");
  REQUIRE(data.size() == 3);
  CHECK(data[2] == Approx(0.0004).epsilon(1e-12));  // mm converted to m
  for (size_t i = 0; i < 3; ++i) CHECK(prediction[i] == Approx(data[i]).epsilon(1e-6));
  CHECK(file.read_doubles("/fit/x") == std::vector<double>{0.001, 0.002, 0.003});
  std::vector<hsize_t> shape;
  file.read_doubles("/fit/history/values", &shape);
  CHECK(shape[0] == file.read_doubles("/fit/history/objective").size());
  CHECK(shape[1] == 1);
  CHECK(file.read_doubles("/fit/history/objective").size() >= 3);
}

TEST_CASE("tirefe.fit with curve_points writes the fitted model on a fine grid and the file's units", "[fitting]") {
  TempDir folder;
  // F = k d^2 with k = 2e7 N/m^2, deflections in mm and forces in kN in the file.
  folder.write("curve.csv", "deflection_mm, force_kN, pressure_kPa\n5, 0.5, 200\n15, 4.5, 220\n10, 2, 210\n");
  const std::string deck = folder.write("fit_curve.lua", R"(
local function law(p, columns)
  local forces = {}
  for i, d in ipairs(columns.deflection) do forces[i] = p.k * d * d * columns.pressure[i] / columns.pressure[i] end
  return forces
end
tirefe.fit{ parameters = { { name = "k", initial = 1e7, lower = 1e5, upper = 1e9 } }, data_file = "curve.csv", data_column = "force",
            model = law, tolerance = 1e-10, output = "grid.h5", curve_points = 11 }
-- A model that returns its values at the data points whatever it is given: no curve.
tirefe.fit{ parameters = { { name = "k", initial = 1e7, lower = 1e5, upper = 1e9 } }, data_file = "curve.csv", data_column = "force",
            model = function(p) return { p.k * 25e-6, p.k * 225e-6, p.k * 100e-6 } end, tolerance = 1e-10,
            output = "points.h5", curve_points = 11 }
)");
  DeckRun run(folder.path("out"));
  run.run(deck);
  const auto file = tirefe::io::Hdf5File::open_read_only(folder.path("out/grid.h5"));
  const std::vector<double> x = file.read_doubles("/fit/curve/x"), curve = file.read_doubles("/fit/curve/prediction");
  REQUIRE(x.size() == 11);
  REQUIRE(curve.size() == 11);
  const double k = file.read_doubles("/fit/parameters/value")[0];
  CHECK(k == Approx(2e7).epsilon(1e-8));
  for (size_t i = 0; i < x.size(); ++i) {
    CHECK(x[i] == Approx(0.005 + 0.001 * static_cast<double>(i)).epsilon(1e-12));  // 5 to 15 mm, in m
    CHECK(curve[i] == Approx(k * x[i] * x[i]).epsilon(1e-12));
  }
  CHECK(file.read_string_attribute("/fit/x", "file_unit") == "mm");
  CHECK(file.read_double_attribute("/fit/x", "to_si") == 1e-3);
  CHECK(file.read_string_attribute("/fit/data", "file_unit") == "kN");
  CHECK(file.read_double_attribute("/fit/data", "to_si") == 1e3);
  const auto points = tirefe::io::Hdf5File::open_read_only(folder.path("out/points.h5"));
  CHECK_FALSE(points.exists("/fit/curve"));
  CHECK(points.read_doubles("/fit/prediction").size() == 3);

  // post/plot_fit.py draws both: the continuous curve, and the values at the data points.
  for (const char* name : {"grid", "points"}) {
    const std::string plot = "/usr/bin/python3 " + std::string(TIREFE_SOURCE_DIR) + "/post/plot_fit.py " +
                             folder.path("out/" + std::string(name) + ".h5") + " > /dev/null";
    CHECK(std::system(plot.c_str()) == 0);
    CHECK(std::filesystem::file_size(folder.path("out/" + std::string(name) + "_fit.png")) > 10000);
  }
}

TEST_CASE("tirefe.fit reports a malformed CSV row and a failing model at the deck line", "[fitting]") {
  TempDir folder;
  folder.write("bad.csv", "deflection_mm, force_N\n1, 10\n2, 20, 30\n");
  const std::string bad_data = folder.write("bad_data.lua",
                                            "local p = 1\n"
                                            "tirefe.fit{ parameters = { { name = \"k\", initial = 1 } },\n"
                                            "  data_file = \"bad.csv\", data_column = \"force\",\n"
                                            "  model = function(p) return { p.k, p.k } end }\n");
  DeckRun run(folder.path("out"));
  CHECK_THROWS_WITH(run.run(bad_data), Contains(bad_data + ":2: macro 'fit': ") &&
                                           Contains("bad.csv:3: expected 2 values (deflection_mm, force_N), found 3"));

  const std::string failing = folder.write("failing.lua",
                                           "tirefe.fit{ parameters = { { name = \"k\", initial = 1 } },\n"
                                           "  data = { 1, 2, 3 },\n"
                                           "  model = function(p)\n"
                                           "    error(\"no contact found\")\n"
                                           "  end }\n");
  DeckRun second(folder.path("out"));
  CHECK_THROWS_WITH(second.run(failing), Contains(failing + ":1: macro 'fit': the model failed at the initial "
                                                            "parameters (k = 1): ") &&
                                             Contains("failing.lua:4: no contact found"));

  const std::string typo = folder.write("typo.lua",
                                        "tirefe.fit{ parameters = { { name = \"k\", intial = 1 } },\n"
                                        "  data = { 1, 2, 3 }, model = function(p) return { 1, 2, 3 } end }\n");
  DeckRun third(folder.path("out"));
  CHECK_THROWS_WITH(third.run(typo), Contains("unknown key 'intial' (did you mean 'initial'?"));
}

TEST_CASE("tirefe.fit returns not_identifiable without values for an ignored parameter", "[fitting]") {
  TempDir folder;
  const std::string deck = folder.write("ignored.lua", R"(
result = tirefe.fit{
  parameters = { { name = "a", initial = 1 }, { name = "unused", initial = 5 } },
  data = { 2, 4, 6, 8 },
  model = function(p) return { p.a, 2 * p.a, 3 * p.a, 4 * p.a } end }
ignored = result.not_identifiable[1]
has_value = result.values.unused ~= nil
)");
  DeckRun run(folder.path("out"));
  run.run(deck);
  CHECK(run.text("result", "status") == "not_identifiable");
  lua_State* L = run.sandbox.state();
  lua_getglobal(L, "ignored");
  CHECK(std::string(lua_tostring(L, -1)) == "unused");
  lua_getglobal(L, "has_value");
  CHECK(lua_toboolean(L, -1) == 0);
  lua_pop(L, 2);
}
