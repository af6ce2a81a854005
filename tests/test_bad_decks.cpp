// Bad decks (tests/bad_decks/): each must stop with a one-line error that names the deck
// file and line and says what is wrong, exit with status 1, and never crash. Each deck
// states its expectation in its first lines:
//   -- expect line N: text that must appear in the message   (N = 0: no line number)
//   -- args: key=value ...                                   (optional command-line parameters)
//   -- keeps: FILE ROWS     (optional: the result file FILE stays readable with at least ROWS history rows)
// "{here}" in these lines stands for the folder of the bad decks.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "io/hdf5_file.hpp"
#include "tirefe/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

struct RunResult {
  int exit_status;
  std::string errors;  // standard error
};

/// The output folder of the runs: one per test process, as suites of several checkouts
/// may run on one machine at the same time; removed when the process ends.
const fs::path& run_folder() {
  struct Folder {
    fs::path path = fs::temp_directory_path() / ("tirefe_bad_decks_" + std::to_string(::getpid()));
    ~Folder() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

RunResult run_tirefe(const std::string& arguments) {
  const fs::path output = run_folder();
  const std::string command =
      std::string(TIREFE_BINARY) + " " + arguments + " --quiet --output-dir " + output.string() + " 2>&1 >/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string errors;
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe)) errors += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), errors};
}

struct Expectation {
  int line = -1;
  std::string text;
  std::string arguments;
  std::string kept_file;
  int kept_rows = 0;
};

std::string with_folder(std::string text, const fs::path& folder) {
  for (size_t at; (at = text.find("{here}")) != std::string::npos;) text.replace(at, 6, folder.string());
  return text;
}

Expectation read_expectation(const fs::path& deck) {
  std::ifstream in(deck);
  Expectation expectation;
  std::string line;
  const std::regex expect_pattern(R"(^-- expect line (\d+): (.*)$)"), args_pattern(R"(^-- args: (.*)$)"),
      keeps_pattern(R"(^-- keeps: (\S+) (\d+)$)");
  for (int i = 0; i < 5 && std::getline(in, line); ++i) {
    std::smatch match;
    if (std::regex_match(line, match, expect_pattern)) {
      expectation.line = std::stoi(match[1]);
      expectation.text = with_folder(match[2], deck.parent_path());
    } else if (std::regex_match(line, match, args_pattern)) {
      expectation.arguments = with_folder(match[1], deck.parent_path());
    } else if (std::regex_match(line, match, keeps_pattern)) {
      expectation.kept_file = match[1];
      expectation.kept_rows = std::stoi(match[2]);
    }
  }
  return expectation;
}

}  // namespace

TEST_CASE("every bad deck gets a clear one-line error with file and line", "[decks][bad]") {
  const fs::path folder = fs::path(TIREFE_TEST_DATA_DIR) / "bad_decks";
  int decks = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".lua") continue;
    const Expectation expectation = read_expectation(entry.path());
    const std::string deck = entry.path().string();
    INFO("deck " << deck);
    REQUIRE(expectation.line >= 0);
    const RunResult result = run_tirefe(deck + " " + expectation.arguments);
    INFO("message: " << result.errors);
    CHECK(result.exit_status == 1);
    CHECK(std::count(result.errors.begin(), result.errors.end(), '\n') == 1);
    CHECK(result.errors.find(expectation.text) != std::string::npos);
    if (expectation.line > 0)
      CHECK(result.errors.rfind("tirefe: " + deck + ":" + std::to_string(expectation.line) + ": ", 0) == 0);
    else
      CHECK(result.errors.find(deck) != std::string::npos);
    if (!expectation.kept_file.empty()) {
      const fs::path kept = run_folder() / expectation.kept_file;
      const auto output = tirefe::io::Hdf5File::open_read_only(kept.string());
      const std::vector<double> time = output.read_doubles("/history/time");
      CHECK(static_cast<int>(time.size()) >= expectation.kept_rows);
      CHECK(std::all_of(time.begin(), time.end(), [](double t) { return std::isfinite(t); }));
    }
    ++decks;
  }
  CHECK(decks >= 25);
}

TEST_CASE("the self-checking decks in inputs/ pass their checks", "[decks]") {
  for (const char* deck :
       {"cantilever_elastica.lua", "cantilever_rollup.lua", "tire_inflation.lua", "ring_modes.lua", "step_cut.lua",
        "loaded_modes_145SR12.lua", "spindle_force.lua", "quarter_car.lua", "fit_ksw_145SR12.lua"}) {
    const std::string path = (fs::path(TIREFE_SOURCE_DIR) / "inputs" / deck).string();
    INFO("deck " << path);
    const RunResult result = run_tirefe(path);
    INFO("errors: " << result.errors);
    CHECK(result.exit_status == 0);
  }
}

TEST_CASE("a vehicle step that fails names the corner whose tire failed", "[decks][vehicle]") {
  // The quarter car at 300 km/h in 50 ms steps: the tire's Newton fails after every cut.
  const std::string deck = (fs::path(TIREFE_SOURCE_DIR) / "inputs" / "quarter_car.lua").string();
  const RunResult result = run_tirefe(deck + " dt=0.05 speed_kmh=300");
  INFO("errors: " << result.errors);
  CHECK(result.exit_status == 1);
  CHECK(std::count(result.errors.begin(), result.errors.end(), '\n') == 1);
  // The line of the rolling run's tirefe.vehicle call, the second in the deck.
  std::ifstream text(deck);
  int line = 0, vehicle_calls = 0, at = 0;
  for (std::string row; std::getline(text, row) && vehicle_calls < 2;) {
    ++line;
    if (row.find("tirefe.vehicle{") != std::string::npos && ++vehicle_calls == 2) at = line;
  }
  REQUIRE(at > 0);
  CHECK(result.errors.find("quarter_car.lua:" + std::to_string(at) + ": macro 'vehicle': vehicle step from t = ") !=
        std::string::npos);
  CHECK(result.errors.find("failed after 4 cuts: the tire of corner 'quarter' failed: the step from t = ") !=
        std::string::npos);
}

TEST_CASE("drum-cleat deck, short version: where the tread meets the cleat moves its peaks by 1 % at most",
          "[decks][drum][phase]") {
  // The cleat moved by quarters of a node spacing (17.06 mm on the tire, 1.150 degrees of the
  // 1.7 m drum): the tread contact samples every chord, so the peak-to-peak forces of the
  // passage hold within the +- 2 % (Fx) and +- 1 % (Fz) of docs/drum_cleat.md's eight phases.
  const std::string deck = (fs::path(TIREFE_SOURCE_DIR) / "inputs" / "drum_cleat.lua").string();
  const double spacing_deg = 0.543 * M_PI / 100 / 0.85 * 180 / M_PI;
  std::vector<double> fx, fz;
  for (int quarter = 0; quarter < 4; ++quarter) {
    const std::string name = "drum_phase_" + std::to_string(quarter) + ".h5";
    char start[64];
    std::snprintf(start, sizeof start, "%.6f", -90.0 + 0.25 * quarter * spacing_deg);
    const RunResult result =
        run_tirefe(deck + " spin_up_time=0.5 end_time=3.0 cleat_start_deg=" + start + " output=" + name);
    INFO("errors: " << result.errors);
    REQUIRE(result.exit_status == 0);
    const auto hdf5 = tirefe::io::Hdf5File::open_read_only((run_folder() / name).string());
    fx.push_back(hdf5.read_double_attribute("/results", "fx_peak_to_peak"));
    fz.push_back(hdf5.read_double_attribute("/results", "fz_peak_to_peak"));
  }
  auto half_spread = [](const std::vector<double>& values) {
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    return 0.5 * (*high - *low) / (0.5 * (*high + *low));
  };
  INFO("Fx " << fx[0] << " " << fx[1] << " " << fx[2] << " " << fx[3] << " N; Fz " << fz[0] << " " << fz[1] << " "
             << fz[2] << " " << fz[3] << " N");
  CHECK(half_spread(fx) <= 0.02);
  CHECK(half_spread(fz) <= 0.01);
}

TEST_CASE("drum-cleat deck, short version: checks, history, parameters, XDMF index and plots", "[decks][drum]") {
  // A 0.5 s spin-up instead of 4 s: the passages at full speed that follow are the same
  // impacts as in the full run (docs/drum_cleat.md); by 3.4 s two of them have rung out, and
  // the summary reads both (the plot's FFT check too).
  const fs::path output = run_folder();
  const std::string deck = (fs::path(TIREFE_SOURCE_DIR) / "inputs" / "drum_cleat.lua").string();
  const RunResult result = run_tirefe(deck + " spin_up_time=0.5 end_time=3.4 check=true output=drum_short.h5");
  INFO("errors: " << result.errors);
  REQUIRE(result.exit_status == 0);

  const fs::path file = output / "drum_short.h5";
  const tirefe::io::Hdf5File hdf5 = tirefe::io::Hdf5File::open_read_only(file.string());
  const std::vector<double> time = hdf5.read_doubles("/history/time");
  const std::vector<double> fz = hdf5.read_doubles("/history/spindle_fz");
  REQUIRE(fz.size() == time.size());
  CHECK(time.back() == Approx(3.4).epsilon(1e-9));
  CHECK(hdf5.read_double_attribute("/results", "cleat_on_s") -
            hdf5.read_double_attribute("/results", "before_cleat_on_s") ==
        Approx(std::acos(-1.0) * 1.7 / (51.3 / 3.6)).epsilon(1e-9));  // a turn apart
  // The drum channels exist from the contact's definition on (after inflation), NaN before.
  const std::vector<double> angle = hdf5.read_doubles("/history/drum_surface_angle");
  CHECK(std::isnan(angle.front()));
  CHECK(angle.back() < -10.0);  // clockwise, several turns
  CHECK(hdf5.read_double_attribute("/parameters", "spin_up_time") == 0.5);
  CHECK(fs::exists(output / "drum_short.xmf"));
  // Spindle forces in wheel axes, the tire heading -x over the drum's top: pressed, Fz is the
  // load (to the deck's 0.1 % press tolerance); the cleat's strike retards the wheel, Fx < 0.
  CHECK(hdf5.read_string_attribute("/", "heading") == "-x");
  const std::vector<double> fx = hdf5.read_doubles("/history/spindle_fx");
  double pressed = 0.0, strike = 0.0;
  const double on = hdf5.read_double_attribute("/results", "cleat_on_s");
  for (size_t i = 0; i < time.size(); ++i) {
    if (time[i] <= 2.0 + 1e-9) pressed = fz[i];  // the pressing ends at 2 s
    if (std::abs(time[i] - on) <= 0.01) strike = std::min(strike, fx[i]);
  }
  CHECK(pressed == Approx(3800.0).epsilon(1e-3));
  CHECK(strike < -2000.0);

  const std::string plot = "/usr/bin/python3 " +
                           (fs::path(TIREFE_SOURCE_DIR) / "post" / "plot_drum_cleat.py").string() + " " +
                           file.string() + " > /dev/null";
  REQUIRE(std::system(plot.c_str()) == 0);
  for (const char* suffix : {"_forces.png", "_impact.png", "_spectrum.png", "_snapshots.png"})
    CHECK(fs::file_size(output / ("drum_short" + std::string(suffix))) > 10000);
  // The general plot of any result file, on the same run.
  const std::string general = "/usr/bin/python3 " +
                              (fs::path(TIREFE_SOURCE_DIR) / "post" / "plot_results.py").string() + " " +
                              file.string() + " > /dev/null 2>&1";
  REQUIRE(std::system(general.c_str()) == 0);
  for (const char* suffix : {"_history.png", "_shapes.png"})
    CHECK(fs::file_size(output / ("drum_short" + std::string(suffix))) > 10000);
}

TEST_CASE("vehicle pothole deck, short version: loads, strikes against converged ones, energy, the plots",
          "[decks][vehicle]") {
  // A 0.5 s ramp and the chuckhole 0.1 s into the cruise instead of 5 s and 1 s: the same
  // crossing at 48 km/h by the left wheels, with the deck's own checks (docs/vehicle.md).
  const fs::path output = run_folder();
  const std::string deck = (fs::path(TIREFE_SOURCE_DIR) / "inputs" / "vehicle_pothole.lua").string();
  const RunResult result = run_tirefe(deck + " settle=0.05 ramp=0.5 cruise=0.45 lead=0.1");
  INFO("errors: " << result.errors);
  REQUIRE(result.exit_status == 0);
  for (const char* corner : {"LF", "RF", "LR", "RR"}) {
    const fs::path file = output / ("vehicle_pothole_" + std::string(corner) + ".h5");
    const tirefe::io::Hdf5File hdf5 = tirefe::io::Hdf5File::open_read_only(file.string());
    const std::vector<double> time = hdf5.read_doubles("/history/time");
    CHECK(time.back() == Approx(3.0).epsilon(1e-9));
    for (const char* channel : {"spindle_fx", "spindle_fz", "vehicle_heave", "vehicle_pitch", "vehicle_roll", "jounce"})
      CHECK(hdf5.read_doubles(std::string("/history/") + channel).size() == time.size());
    CHECK(hdf5.read_string_attribute("/", "heading") == "+x");
  }
  {
    // The steps: the road's travel in a step as at full speed in dt = 0.5 ms, up to dt_max =
    // 2 ms, while it is still (settling from 2 s) or slow (the ramp from 2.05 s, in windows of
    // 0.1 s, the speed at the window's end); 0.5 ms at full speed, 0.2 ms at the chuckhole.
    const auto hdf5 = tirefe::io::Hdf5File::open_read_only((output / "vehicle_pothole_LF.h5").string());
    const std::vector<double> time = hdf5.read_doubles("/history/time");
    auto step_after = [&](double t) {
      const auto next = std::upper_bound(time.begin(), time.end(), t);
      REQUIRE((next != time.begin() && next != time.end()));
      return *next - *(next - 1);
    };
    CHECK(step_after(2.02) == Approx(2e-3).epsilon(1e-9));        // settling
    CHECK(step_after(2.10) == Approx(2e-3).epsilon(1e-9));        // ramp to 20 % of the speed
    CHECK(step_after(2.30) == Approx(5e-4 / 0.6).epsilon(1e-9));  // ramp to 60 %
    CHECK(step_after(2.50) == Approx(5e-4).epsilon(1e-9));        // ramp to full speed
    CHECK(step_after(2.60) == Approx(5e-4).epsilon(1e-9));        // at speed
    CHECK(step_after(2.70) == Approx(2e-4).epsilon(1e-9));        // crossing the chuckhole
  }
  // The left wheels' strikes against this protocol's converged ones (regression: the same
  // run with dt_pothole = 50 us; at 200, 100 and 50 us the peaks move by 2.9 % at most,
  // docs/vehicle.md), and their energy account (the deck checks it too).
  struct Strike {
    const char* corner;
    double time, fz, fx_low, fx_high, fz_filtered, fx_low_filtered, fx_high_filtered;
  };
  for (const Strike& expected : {Strike{"LF", 2.6982, 15240, -5124, 4836, 15129, -5044, 4633},
                                 Strike{"LR", 2.9014, 12253, -4207, 4304, 12164, -4191, 4160}}) {
    INFO(expected.corner);
    const auto hdf5 = tirefe::io::Hdf5File::open_read_only(
        (output / ("vehicle_pothole_" + std::string(expected.corner) + ".h5")).string());
    auto result = [&](const char* key) { return hdf5.read_double_attribute("/results", std::string("strike_") + key); };
    CHECK(result("time") == Approx(expected.time).margin(0.001));
    CHECK(result("fz_peak") == Approx(expected.fz).epsilon(0.03));
    CHECK(result("fx_low") == Approx(expected.fx_low).epsilon(0.03));
    CHECK(result("fx_high") == Approx(expected.fx_high).epsilon(0.03));
    CHECK(result("fz_peak_filtered") == Approx(expected.fz_filtered).epsilon(0.03));
    CHECK(result("fx_low_filtered") == Approx(expected.fx_low_filtered).epsilon(0.03));
    CHECK(result("fx_high_filtered") == Approx(expected.fx_high_filtered).epsilon(0.03));
    CHECK(std::abs(result("energy_error")) < 0.02 * result("surface_work"));
    CHECK(result("step_error") < 0.02 * result("surface_work"));
    CHECK(result("contact_jump") < 0.5);
  }
  const std::string plot = "/usr/bin/python3 " + (fs::path(TIREFE_SOURCE_DIR) / "post" / "plot_vehicle.py").string() +
                           " 2.6 3.0 " + (output / "vehicle_pothole_LF.h5").string() + " " +
                           (output / "vehicle_pothole_LR.h5").string() + " > /dev/null";
  REQUIRE(std::system(plot.c_str()) == 0);
  CHECK(fs::file_size(output / "vehicle_pothole_LF_spindle.png") > 10000);
}

TEST_CASE("a deck whose self-check fails exits with status 3", "[decks]") {
  const fs::path deck = fs::temp_directory_path() / "tirefe_failing_check.lua";
  std::ofstream(deck) << "tirefe.check{ name = \"one is two\", value = 1, expected = 2, tolerance = 0.5 }\n";
  CHECK(run_tirefe(deck.string()).exit_status == 3);
  fs::remove(deck);
}

TEST_CASE("a run that fails mid-way keeps a readable file with every completed step", "[decks][output]") {
  const fs::path deck = fs::temp_directory_path() / "tirefe_fails_midway.lua";
  std::ofstream(deck) << R"(
local model = tirefe.model{ title = "fails at t = 0.4" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
-- At t = 0.4 the support of node a is released: a mechanism no step cut can save.
model:load{ node = b, fy = -1 }
model:output{ file = "fails_midway.h5", fields_every = 1 }
model:history{ name = "tip_uy", node = b, dof = "uy" }
model:step_control{ max_cuts = 2 }
model:solve{ to = 0.3, dt = 0.1 }
model:release{ node = a, dofs = { "ux", "uy", "rz" } }
model:solve{ to = 1.0 }
)";
  const RunResult result = run_tirefe(deck.string());
  INFO(result.errors);
  CHECK(result.exit_status == 1);
  CHECK(result.errors.find("could not be solved") != std::string::npos);
  const fs::path file = run_folder() / "fails_midway.h5";
  tirefe::io::Hdf5File output = tirefe::io::Hdf5File::open_read_only(file.string());
  const std::vector<double> time = output.read_doubles("/history/time");
  REQUIRE(time.size() == 3);
  CHECK(time.back() == Approx(0.3));
  CHECK(output.read_doubles("/history/tip_uy").size() == 3);
  std::vector<hsize_t> shape;
  output.read_doubles("/fields/displacement", &shape);
  CHECK(shape[0] == 3);
  fs::remove(deck);
}
