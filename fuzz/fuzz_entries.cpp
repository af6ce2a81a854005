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
  require(message.find(file.filename().string()) != std::string::npos,
          "the error does not name the file: " + message);
}

// Macros that only describe the model or query it: solving macros (step, solve, modal,
// fit) would let an input ask for unbounded work, and output macros write files.
const char* const kMacros[] = {"node",       "node_set", "section",      "beam",    "load_function", "fix",
                               "prescribe",  "release",  "load",         "integrator", "newton",     "step_control",
                               "dt",         "history",  "value",        "time",    "print",         "initial",
                               "surface",    "contact",  "contact_value", "checkpoint"};

const char* kPrelude = R"(local model = tirefe.model{ title = "fuzz" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
local c = model:node{ x = 2, y = 0.5 }
model:node_set{ name = "s", nodes = { a, b, c } }
model:section{ name = "beam", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "beam", nodes = { a, b, c } }
model:fix{ node = a }
)";

}  // namespace

void deck_macro(const uint8_t* data, size_t size) {
  if (size == 0) return;
  const std::string macro = kMacros[data[0] % (sizeof kMacros / sizeof kMacros[0])];
  const std::string arguments(reinterpret_cast<const char*>(data) + 1, size - 1);
  const fs::path deck = write_file("deck.lua", std::string(kPrelude) + "model:" + macro + "(" + arguments + ")\n");
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
    for (const Eigen::Vector2d& point : {points.front(), points.back(), Eigen::Vector2d(0.5 * (points.front() + points.back()))}) {
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
