#include "fuzz/fuzz_entries.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "contact/road_file.hpp"
#include "core/mesh.hpp"
#include "fitting/curve_data.hpp"
#include "io/hdf5_file.hpp"
#include "io/teim_orbit.hpp"
#include "macros/deck_session.hpp"
#include "macros/lua_sandbox.hpp"
#include "macros/macro_table.hpp"
#include "tirefe/source_paths.hpp"

namespace tirefe::fuzz {

namespace {

namespace fs = std::filesystem;

/// A private folder for the files the parsers read (one per process: fuzzers run in parallel).
const fs::path& scratch() {
  static const fs::path folder = [] {
    fs::path path = fs::temp_directory_path() / ("tirefe_fuzz_" + std::to_string(getpid()));
    fs::create_directories(path);
    return path;
  }();
  return folder;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path path = scratch() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path;
}

void require(bool condition, const std::string& what) {
  if (!condition) throw FuzzFailure(what);
}

void require_names_file(const std::exception& error, const fs::path& file) {
  const std::string message = error.what();
  require(message.find(file.filename().string()) != std::string::npos, "the error does not name the file: " + message);
}

/// Runs a deck through the sandbox and the macro layer: it runs or stops with a DeckError naming it.
void run_deck(const fs::path& deck) {
  macros::DeckSession session;
  session.output_dir = (scratch() / "results").string();
  session.deck_path = deck.string();
  session.quiet = true;
  macros::LuaSandbox sandbox(TIREFE_LUA_DIR);
  try {
    macros::install_macros(sandbox, session);
    sandbox.run_file(deck.string());
  } catch (const macros::DeckError& error) {
    require_names_file(error, deck);
  }
}

// Macros that only describe the model or query it: solving macros (step, solve, modal,
// fit) would let free-form arguments ask for unbounded work (deck_sequence calls them
// with bounded ones), and output macros write files.
const char* const kMacros[] = {"node",      "node_set", "section",       "beam",       "load_function", "fix",
                               "prescribe", "release",  "load",          "integrator", "newton",        "step_control",
                               "dt",        "history",  "value",         "time",       "print",         "initial",
                               "surface",   "contact",  "contact_value", "checkpoint"};

const char* kPrelude = R"(local model = tirefe.model{ title = "fuzz" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
local c = model:node{ x = 2, y = 0.5 }
model:node_set{ name = "s", nodes = { a, b, c } }
model:section{ name = "beam", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "beam", nodes = { a, b, c } }
model:fix{ node = a }
)";

// deck_sequence: a three-node beam held at node 1, loaded at node 3 by "cb1" (f = t). The
// load functions cb1..cb6 each call back into the model while it assembles (at most
// three times each, so that a callback that steps cannot recurse without end).
const char* kSequencePrelude = R"(local model = tirefe.model{ title = "fuzz sequence" }
local n = { model:node{ x = 0, y = 0 }, model:node{ x = 0.5, y = 0 }, model:node{ x = 1, y = 0.1 } }
model:section{ name = "beam", EA = 1e5, GA = 1e5, EI = 10, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "beam", nodes = { n[1], n[2], n[3] } }
model:fix{ node = n[1] }
model:step_control{ max_cuts = 3, min_dt = 1e-4 }
model:newton{ max_iterations = 8 }
model:dt{ value = 0.01 }
local function callback(action)
  local calls = 0
  return function(t)
    calls = calls + 1
    if calls <= 3 then action() end
    return t
  end
end
)";

// What the callbacks do: queries, re-entrant solves, changes of the model while it
// assembles, errors, a non-finite factor, the model dropped and collected.
const char* const kCallbacks[] = {
    "model:time()",
    "model:value{ node = n[2], dof = 'uy', quantity = 'reaction' }",
    "model:step{ dt = 0.001 }",
    "model:solve{ to = model:time() + 0.002 }",
    "n[#n + 1] = model:node{ x = 0.5 * #n, y = 0 }",
    "model:load{ node = n[2], fx = 1 }",
    "model:fix{ node = n[2] }",
    "model:release{ node = n[1], dofs = { 'rz' } }",
    "model:integrator{ type = 'hht', alpha = -0.1 }",
    "model:modal{ modes = 1 }",
    "model:beam{ section = 'beam', nodes = { n[2], n[#n] } }",
    "error('callback failed')",
    "error({})",
    "collectgarbage()",
    "model = nil collectgarbage()",
};
constexpr int kCallbackCount = 6;  // cb1..cb6, drawn from kCallbacks by the first bytes

/// The deck line for call 'op' with argument byte 'a' (node and load-function choices, sizes).
std::string sequence_call(uint8_t op, uint8_t a) {
  const std::string node = "n[1 + " + std::to_string(a) + " % #n]";
  const std::string dof = std::string("'") + (a % 3 == 0 ? "ux" : a % 3 == 1 ? "uy" : "rz") + "'";
  const std::string function = "'cb" + std::to_string(1 + a % kCallbackCount) + "'";
  const double dts[] = {1e-3, 0.01, 0.05, 0.2};
  switch (op % 18) {
    case 0: return "model:step{ dt = " + std::to_string(dts[a % 4]) + " }";
    case 1: return "model:step()";
    case 2: return "model:solve{ to = model:time() + " + std::to_string(0.01 * (1 + a % 4)) + " }";
    case 3: {
      const char* types[] = {"type = 'static'", "type = 'newmark'", "type = 'hht', alpha = -0.05"};
      return std::string("model:integrator{ ") + types[a % 3] + " }";
    }
    case 4:
      return "model:load{ node = " + node + ", fy = " + std::to_string(static_cast<int>(a) - 128) +
             ", load_function = " + function + " }";
    case 5:
      return "model:prescribe{ node = " + node + ", dof = " + dof + ", value = 0.01, load_function = " + function +
             " }";
    case 6: return "model:fix{ node = " + node + " }";
    case 7: return "model:release{ node = " + node + ", dofs = { " + dof + " } }";
    case 8:
      return "n[#n + 1] = model:node{ x = 0.5 * #n, y = " + std::to_string(0.01 * (a % 7)) +
             " } model:beam{ section = 'beam', nodes = { n[#n - 1], n[#n] } }";
    case 9: return "model:modal{ modes = " + std::to_string(1 + a % 3) + " }";
    case 10: return "model:value{ node = " + node + ", dof = " + dof + " }";
    case 11: return "collectgarbage()";
    case 12: return "model:newton{ max_iterations = " + std::to_string(1 + a % 10) + " }";
    case 13: return "model:step_control{ max_cuts = " + std::to_string(a % 4) + ", min_dt = 1e-4 }";
    case 14: return "pcall(model.step, model)";  // a failed step caught by the deck, then more calls
    case 15: return "model:history{ name = 'h" + std::to_string(a) + "', node = " + node + ", dof = " + dof + " }";
    case 16: return "model:initial{ node = " + node + ", dof = " + dof + ", velocity = 0.1 }";
    default: return "model:print{ node = " + node + " }";
  }
}

}  // namespace

std::string sequence_deck(const uint8_t* data, size_t size) {
  constexpr size_t kMaxCalls = 24;  // with the small steps: well under a second of work
  std::string deck = kSequencePrelude;
  size_t at = 0;
  for (int f = 1; f <= kCallbackCount; ++f, ++at) {
    const uint8_t choice = at < size ? data[at] : 0;
    deck += "model:load_function{ name = 'cb" + std::to_string(f) + "', fn = callback(function() " +
            kCallbacks[choice % (sizeof kCallbacks / sizeof kCallbacks[0])] + " end) }\n";
  }
  deck += "model:load{ node = n[3], fy = -1, load_function = 'cb1' }\n";
  for (size_t calls = 0; at + 1 < size && calls < kMaxCalls; at += 2, ++calls)
    deck += sequence_call(data[at], data[at + 1]) + "\n";
  return deck;
}

void deck_sequence(const uint8_t* data, size_t size) {
  run_deck(write_file("sequence.lua", sequence_deck(data, size)));
}

void deck_macro(const uint8_t* data, size_t size) {
  if (size == 0) return;
  const std::string macro = kMacros[data[0] % (sizeof kMacros / sizeof kMacros[0])];
  const std::string arguments(reinterpret_cast<const char*>(data) + 1, size - 1);
  run_deck(write_file("deck.lua", std::string(kPrelude) + "model:" + macro + "(" + arguments + ")\n"));
}

void road_profile(const uint8_t* data, size_t size) {
  const fs::path file = write_file("road.txt", std::string(reinterpret_cast<const char*>(data), size));
  std::vector<Eigen::Vector2d> points;
  try {
    points = RoadProfile::read_points(file.string());
  } catch (const ModelError& error) {
    require_names_file(error, file);
    return;
  }
  require(points.size() >= 2, "a profile of fewer than two points was accepted");
  for (size_t i = 0; i < points.size(); ++i) {
    require(points[i].allFinite(), "a non-finite point was accepted");
    require(i == 0 || points[i].x() >= points[i - 1].x(), "a decreasing x was accepted");
  }
  try {
    const RoadProfile profile(points, 0.01);
    for (const Eigen::Vector2d& point :
         {points.front(), points.back(), Eigen::Vector2d(0.5 * (points.front() + points.back()))}) {
      const SurfaceProjection projection = profile.project(point + Eigen::Vector2d(0.0, 0.1), 0.0);
      require(std::isfinite(projection.gap) && projection.normal.allFinite(), "a projection is not finite");
    }
  } catch (const ModelError&) {
    // A radius that does not fit the corners, a repeated point: a clear error is the answer.
  }
}

void curve_data(const uint8_t* data, size_t size) {
  const fs::path file = write_file("data.csv", std::string(reinterpret_cast<const char*>(data), size));
  try {
    const fitting::CurveData curve = fitting::CurveData::read_csv(file.string());
    for (const fitting::DataColumn& column : curve.columns()) {
      require(column.values.size() == curve.rows(), "columns of different lengths were accepted");
      for (double value : column.values) require(std::isfinite(value), "a non-finite value was accepted");
    }
  } catch (const fitting::CurveDataError& error) {
    require_names_file(error, file);
  }
}

namespace {

/// An accepted profile: at least two finite points, x never decreasing.
void require_profile(const std::vector<Eigen::Vector2d>& points) {
  require(points.size() >= 2, "a profile of fewer than two points was accepted");
  for (size_t i = 0; i < points.size(); ++i) {
    require(points[i].allFinite(), "a non-finite road point was accepted");
    require(i == 0 || points[i].x() >= points[i - 1].x(), "a decreasing x was accepted");
  }
}

}  // namespace

void road_file(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  struct Reading {
    const char* name;
    std::optional<RoadTrack> track;
    std::optional<double> v;
  };
  const Reading readings[] = {{"road.csv", std::nullopt, std::nullopt},
                              {"road.csv", RoadTrack::Left, std::nullopt},
                              {"road.csv", RoadTrack::Right, std::nullopt},
                              {"road.crg", std::nullopt, std::nullopt},
                              {"road.crg", std::nullopt, 0.37},
                              {"road.crg", std::nullopt, -1e300},
                              {"road.txt", std::nullopt, std::nullopt}};
  for (const Reading& reading : readings) {
    const fs::path file = write_file(reading.name, text);
    try {
      require_profile(read_road_profile(file.string(), reading.track, reading.v));
    } catch (const ModelError& error) {
      require_names_file(error, file);
    } catch (const fitting::CurveDataError& error) {
      require_names_file(error, file);
    }
  }
}

void property_file(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const fs::path tire = write_file("tire.tir", text);
  std::unique_ptr<lua_State, void (*)(lua_State*)> state(luaL_newstate(), lua_close);
  try {
    macros::push_tire_property_file(state.get(), tire.string());
    lua_pushnil(state.get());
    while (lua_next(state.get(), -2)) {
      require(lua_type(state.get(), -1) == LUA_TNUMBER && std::isfinite(lua_tonumber(state.get(), -1)),
              "a tire parameter that is not a finite number was accepted");
      lua_pop(state.get(), 1);
    }
  } catch (const io::TeimOrbitError& error) {
    require_names_file(error, tire);
  }
  const fs::path road = write_file("road.rdf", text);
  for (const RoadTrack track : {RoadTrack::Left, RoadTrack::Right}) {
    try {
      const RoadShape shape = read_road_data_file(road.string(), track);
      for (size_t i = 0; i < shape.points.size(); ++i) {
        require(shape.points[i].allFinite(), "a non-finite road point was accepted");
        require(i == 0 || shape.points[i].x() >= shape.points[i - 1].x(), "a decreasing x was accepted");
      }
      require(std::isfinite(shape.level) && std::isfinite(shape.diameter), "a non-finite road was accepted");
    } catch (const io::TeimOrbitError& error) {
      require_names_file(error, road);
    }
  }
}

}  // namespace tirefe::fuzz
