#include "fuzz/fuzz_entries.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "core/mesh.hpp"
#include "fitting/curve_data.hpp"
#include "formats/road_file.hpp"
#include "formats/teim_orbit.hpp"
#include "include/tirefe.h"
#include "io/hdf5_file.hpp"
#include "deck/checkpoint.hpp"
#include "deck/deck_session.hpp"
#include "deck/lua_sandbox.hpp"
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

/// Runs a deck through the sandbox and the macro layer, restarted from 'restart' if given:
/// it runs or stops with a DeckError naming it. Returns whether it ran to its end.
bool run_deck(const fs::path& deck, std::shared_ptr<const macros::Checkpoint> restart = nullptr,
              const fs::path& output = scratch() / "results") {
  macros::DeckSession session;
  session.output_dir = output.string();
  session.deck_path = deck.string();
  session.quiet = true;
  session.restart = std::move(restart);
  macros::LuaSandbox sandbox(TIREFE_LUA_DIR);
  try {
    macros::install_macros(sandbox, session);
    sandbox.run_file(deck.string());
  } catch (const macros::DeckError& error) {
    require_names_file(error, deck);
    return false;
  }
  return !session.restart;  // a restart's checkpoint loaded (a deck ending before it fails, as tirefe does)
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
  } catch (const formats::TeimOrbitError& error) {
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
    } catch (const formats::TeimOrbitError& error) {
      require_names_file(error, road);
    }
  }
}

// --- checkpoint_file --------------------------------------------------------------------

namespace {

// A beam run that writes a checkpoint between two solves, and is restarted from it.
const char* kCheckpointDeck = R"(local model = tirefe.model{ title = "fuzz checkpoint" }
local n = { model:node{ x = 0, y = 0 }, model:node{ x = 0.5, y = 0 }, model:node{ x = 1, y = 0.1 } }
model:section{ name = "beam", EA = 1e5, GA = 1e5, EI = 10, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "beam", nodes = n }
model:fix{ node = n[1] }
model:load{ node = n[3], fy = -1 }
model:output{ file = "run.h5", fields_every = 2 }
model:history{ name = "tip_uy", node = n[3], dof = "uy" }
model:integrator{ type = "newmark" }
model:step_control{ max_cuts = 3, min_dt = 1e-4 }
model:solve{ to = 0.02, dt = 0.005 }
model:checkpoint{ file = "ck.h5" }
model:solve{ to = 0.04 }
)";

/// A number of the checkpoint that an input may change: an attribute, or an entry of a dataset.
struct Place {
  std::string object, name;  // an attribute; or name empty: the dataset 'object'
  size_t entry = 0;
  bool bytes = false;  // a dataset of bytes (an element block's history)
  bool integers = false;
};

/// The reference checkpoint (written once per process) and the places of its numbers.
struct ReferenceCheckpoint {
  fs::path deck, file;
  std::vector<Place> places;
};

const ReferenceCheckpoint& reference_checkpoint() {
  static const ReferenceCheckpoint reference = [] {
    ReferenceCheckpoint made;
    made.deck = write_file("checkpoint.lua", kCheckpointDeck);
    const fs::path output = scratch() / "reference";
    fs::remove_all(output);
    if (!run_deck(made.deck, nullptr, output)) throw FuzzFailure("the checkpoint deck does not run");
    made.file = output / "ck.h5";
    const macros::Checkpoint checkpoint = macros::read_checkpoint(made.file.string());
    auto attribute = [&](const std::string& object, const std::string& name) { made.places.push_back({object, name}); };
    auto entries = [&](const std::string& dataset, size_t count, bool bytes, bool integers) {
      for (size_t k = 0; k < count; ++k) made.places.push_back({dataset, "", k, bytes, integers});
    };
    CarriedState carried = checkpoint.analysis;
    CarriedState::for_each_field(carried, [&](const char* path, const auto& field) {
      using Field = std::decay_t<decltype(field)>;
      if constexpr (std::is_same_v<Field, Eigen::VectorXd>) {
        entries(path, static_cast<size_t>(field.size()), false, false);
      } else {
        const std::string text = path;
        const size_t slash = text.rfind('/');
        attribute(slash == 0 ? "/" : text.substr(0, slash), text.substr(slash + 1));
      }
    });
    for (const char* name : {"model_index", "node_count"}) attribute("/", name);
    attribute("/blocks", "count");
    for (size_t b = 0; b < checkpoint.blocks.size(); ++b) {
      const std::string group = "/blocks/" + std::to_string(b);
      for (const char* name : {"bytes_per_element", "elements"}) attribute(group, name);
      entries(group + "/history", checkpoint.blocks[b].history.size(), true, false);
    }
    for (const char* name : {"has_output", "steps_recorded", "count"}) attribute("/rows", name);
    for (size_t r = 0; r < checkpoint.rows.size(); ++r) {
      const std::string group = "/rows/" + std::to_string(r);
      attribute(group, "rows");
      entries(group + "/values", std::min<size_t>(checkpoint.rows[r].values.size(), 8), false, false);
      entries(group + "/row_shape", checkpoint.rows[r].row_shape.size(), false, true);
    }
    return made;
  }();
  return reference;
}

/// The value of a change: one of the numbers that break readers (a palette byte below 32),
/// or the eight bytes as they are.
double changed_value(const uint8_t* bytes) {
  static const double kPalette[] = {std::nan(""), INFINITY,     -INFINITY,    0.0,           -1.0,
                                    1.0,          2147483647.0, 2147483648.0, -2147483649.0, 9007199254740993.0,
                                    1e300,        -1e300,       0.5,          1e-300,        4294967296.0,
                                    -0.0,         3.0,          1e18,         -2.0,          1.5};
  if (bytes[0] < 32) return kPalette[bytes[1] % (sizeof kPalette / sizeof kPalette[0])];
  double value;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

constexpr size_t kChangeBytes = 10;  // two for the place, eight for the value
constexpr size_t kMostChanges = 8;

std::string place_text(const Place& place) {
  return place.name.empty() ? place.object + "[" + std::to_string(place.entry) + "]"
                            : (place.object == "/" ? "" : place.object) + "/" + place.name;
}

/// Writes the reference checkpoint with the changes of 'data' to 'file'.
void write_changed_checkpoint(const uint8_t* data, size_t size, const fs::path& file) {
  const ReferenceCheckpoint& reference = reference_checkpoint();
  fs::copy_file(reference.file, file, fs::copy_options::overwrite_existing);
  io::Hdf5File hdf5 = io::Hdf5File::open_read_write(file.string());
  for (size_t at = 0, changes = 0; at + kChangeBytes <= size && changes < kMostChanges; at += kChangeBytes, ++changes) {
    const Place& place = reference.places[(data[at] | data[at + 1] << 8) % reference.places.size()];
    const double value = changed_value(data + at + 2);
    if (!place.name.empty()) {
      hdf5.write_attribute(place.object, place.name, value);
    } else if (place.bytes) {
      std::vector<unsigned char> bytes = hdf5.read_bytes(place.object);
      bytes.at(place.entry) = static_cast<unsigned char>(data[at + 2] ^ data[at + 9]);
      hdf5.remove(place.object);
      hdf5.write_bytes(place.object, bytes);
    } else if (place.integers) {
      std::vector<long long> values = hdf5.read_ints(place.object);
      values.at(place.entry) = std::isfinite(value) && std::abs(value) < 9e18 ? static_cast<long long>(value) : -1;
      hdf5.remove(place.object);
      hdf5.write_int_vector(place.object, values);
    } else {
      std::vector<double> values = hdf5.read_doubles(place.object);
      values.at(place.entry) = value;
      hdf5.remove(place.object);
      hdf5.write_vector(place.object, values);
    }
  }
  hdf5.close();
}

}  // namespace

std::string checkpoint_changes(const uint8_t* data, size_t size) {
  const ReferenceCheckpoint& reference = reference_checkpoint();
  std::string text;
  for (size_t at = 0, changes = 0; at + kChangeBytes <= size && changes < kMostChanges; at += kChangeBytes, ++changes) {
    const Place& place = reference.places[(data[at] | data[at + 1] << 8) % reference.places.size()];
    char value[32];
    std::snprintf(value, sizeof value, "%.17g", changed_value(data + at + 2));
    text += place_text(place) + " = " + (place.bytes ? "a byte" : value) + "\n";
  }
  return text;
}

void checkpoint_file(const uint8_t* data, size_t size) {
  const ReferenceCheckpoint& reference = reference_checkpoint();
  const fs::path file = scratch() / "changed.ckpt.h5";
  write_changed_checkpoint(data, size, file);
  std::shared_ptr<const macros::Checkpoint> checkpoint;
  try {
    checkpoint = std::make_shared<macros::Checkpoint>(macros::read_checkpoint(file.string()));
  } catch (const io::IoError& error) {
    require_names_file(error, file);
    return;
  }
  const fs::path output = scratch() / "restarted";
  fs::remove_all(output);
  if (!run_deck(reference.deck, checkpoint, output)) return;  // refused at a deck line (another model, ...)
  const io::Hdf5File result = io::Hdf5File::open_read_only((output / "run.h5").string());
  for (double time : result.read_doubles("/history/time"))
    require(std::isfinite(time), "a restart wrote a time that is not finite");
}

// --- capi_calls ---------------------------------------------------------------------------

namespace {

/// Reads doubles and choices from the input bytes (zeros once they run out).
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool done() const { return at_ >= size_; }
  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  /// A number a host might pass: one that breaks readers (NaN, infinities, 1e-12, 1e300,
  /// ...), a plausible one, or eight raw bytes.
  double number() {
    static const double kPalette[] = {std::nan(""), INFINITY, -INFINITY, 0.0,  -0.0,  1e-12, 1e-7, 1e-3,
                                      -1e-3,        1e300,    -1e300,    0.01, -0.01, 0.1,   1.0,  -0.4};
    const uint8_t kind = byte();
    if (kind < 160) return kPalette[kind % (sizeof kPalette / sizeof kPalette[0])];
    if (kind < 240) return (static_cast<int>(byte()) - 128) * 1e-4;  // millimetres around the spindle
    uint8_t bytes[8];
    for (uint8_t& b : bytes) b = byte();
    double value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

bool known_status(tirefe_status status) { return status >= TIREFE_OK && status <= TIREFE_CANCELLED; }

void require_answer(tirefe_status status, const char* message, const std::string& call) {
  require(known_status(status), call + ": unknown status " + std::to_string(status));
  if (status == TIREFE_OK) return;
  require(message && message[0] != '\0', call + ": failed without a message");
  require(std::strchr(message, '\n') == nullptr, call + ": a message of more than one line: " + message);
}

template <size_t N>
bool all_finite(const double (&values)[N]) {
  for (double value : values)
    if (!std::isfinite(value)) return false;
  return true;
}

/// The committed state before and after a trial step: the same time, position and velocity
/// bit for bit, the same force but for round-off (the first step after a restore computes
/// the committed reactions anew: 1e-12 N of inflation becomes 0).
bool unchanged(const tirefe_spindle_state& before, const tirefe_spindle_state& after) {
  bool same = std::memcmp(&before.time, &after.time, sizeof before.time) == 0 &&
              std::memcmp(before.position, after.position, sizeof before.position) == 0 &&
              std::memcmp(before.velocity, after.velocity, sizeof before.velocity) == 0;
  for (int c = 0; c < 3; ++c)
    same = same && std::abs(before.force[c] - after.force[c]) <= 1e-6 * (1.0 + std::abs(before.force[c]));
  return same;
}

/// The tire every input starts from: opened once, its first state saved.
struct FuzzTire {
  tirefe_tire* tire = nullptr;
  tirefe_saved_state* start = nullptr;
};

const FuzzTire& fuzz_tire() {
  static const FuzzTire made = [] {
    FuzzTire opened;
    const tirefe_parameter coarse[] = {{"elements", 40}};
    char error[512];
    if (tirefe_open("tires.145SR12", coarse, 1, nullptr, &opened.tire, error, sizeof error) != TIREFE_OK ||
        tirefe_save_state(opened.tire, &opened.start) != TIREFE_OK)
      throw FuzzFailure(std::string("cannot open the fuzzed tire: ") + error);
    return opened;
  }();
  return made;
}

// Not 'elements': a large tire is bounded by the element limit, and what it costs (its
// contact's stiffness, growing with the square of the elements) is not what this target seeks.
const char* const kParameterNames[] = {"pressure",        "k_sw",    "rim_mass", "tread_EA", "outer_diameter",
                                       "sidewall_length", "presure", ""};

}  // namespace

void capi_calls(const uint8_t* data, size_t size) {
  const FuzzTire& fuzzed = fuzz_tire();
  tirefe_tire* tire = fuzzed.tire;
  require(tirefe_restore_state(tire, fuzzed.start) == TIREFE_OK, "the start state cannot be restored");
  ByteReader in(data, size);
  std::vector<tirefe_saved_state*> saved;
  tirefe_spindle_force reply{};
  tirefe_spindle_state before{}, after{};
  char error[256];
  for (int calls = 0; calls < 16 && !in.done(); ++calls) {
    const uint8_t op = in.byte() % 12;
    tirefe_status status = TIREFE_OK;
    switch (op) {
      case 0:
      case 1: {  // a trial step, by position or by velocity; a failure leaves the committed state
        tirefe_state(tire, &before);
        const double h = in.number(), a = in.number(), b = in.number(), c = in.number();
        const double velocity[3] = {a, b, c};
        const tirefe_spindle_motion motion{h, a, b, c};
        status = op == 0 ? tirefe_solve(tire, &motion, &reply) : tirefe_solve_velocity(tire, h, velocity, &reply);
        require_answer(status, tirefe_message(tire), "solve");
        if (status == TIREFE_OK) {
          require(all_finite(reply.force) && std::isfinite(reply.time), "a solved step's force is not finite");
          for (const auto& row : reply.jacobian) require(all_finite(row), "a solved step's Jacobian is not finite");
        }
        tirefe_state(tire, &after);
        require(unchanged(before, after), "a trial step changed the committed state");
        continue;  // its answer is checked; the state call after it cleared the message
      }
      case 2: status = tirefe_commit(tire); break;
      case 3: status = tirefe_revert(tire); break;
      case 4:
        status = tirefe_state(tire, &after);
        require(status == TIREFE_OK && all_finite(after.position) && all_finite(after.velocity) &&
                    all_finite(after.force) && std::isfinite(after.time),
                "the committed state is not finite");
        break;
      case 5:
        if (saved.size() < 4) {
          saved.push_back(nullptr);
          status = tirefe_save_state(tire, &saved.back());
        }
        break;
      case 6:
        status = tirefe_restore_state(tire, saved.empty() ? fuzzed.start : saved[in.byte() % saved.size()]);
        break;
      case 7:  // a state freed: once for real, then the stale handle again
        if (!saved.empty()) {
          tirefe_saved_state* freed = saved[in.byte() % saved.size()];
          status = tirefe_free_state(freed);
          saved.erase(std::find(saved.begin(), saved.end(), freed));
          require(tirefe_restore_state(tire, freed) == TIREFE_INVALID_ARGUMENT, "a freed state was restored");
          require(tirefe_free_state(freed) == TIREFE_INVALID_ARGUMENT, "a state was freed twice");
        }
        break;
      case 8: {  // made-up handles are refused without being read
        long words[4] = {in.byte(), in.byte(), in.byte(), in.byte()};
        tirefe_tire* made_up = reinterpret_cast<tirefe_tire*>(words);
        require(tirefe_commit(made_up) == TIREFE_INVALID_ARGUMENT && tirefe_close(made_up) == TIREFE_INVALID_ARGUMENT,
                "a made-up handle was taken for a tire");
        break;
      }
      case 9: {  // another tire opened with overrides and options from the bytes, then closed
        tirefe_parameter overrides[2];
        const size_t count = in.byte() % 3;
        for (size_t k = 0; k < count; ++k)
          overrides[k] = {kParameterNames[in.byte() % (sizeof kParameterNames / sizeof kParameterNames[0])],
                          in.number()};
        tirefe_options options;
        tirefe_default_options(&options);
        if (in.byte() % 2) {
          options.friction = in.number();
          options.hht_alpha = in.number();
          options.free_spin = static_cast<int>(in.byte() % 4) - 1;
          options.heading = static_cast<int>(in.byte() % 4) - 2;
        }
        tirefe_tire* other = nullptr;
        status = tirefe_open("tires.145SR12", overrides, count, &options, &other, error, sizeof error);
        require_answer(status, error, "open");
        require((status == TIREFE_OK) == (other != nullptr), "open's handle and status disagree");
        if (other) require(tirefe_close(other) == TIREFE_OK, "an opened tire does not close");
        continue;
      }
      case 10: {  // a static curve of up to three deflections
        double deflections[3], forces[3];
        const size_t n = in.byte() % 4;
        for (size_t k = 0; k < n; ++k) deflections[k] = in.number();
        tirefe_parameter coarse[] = {{"elements", 24}};
        status = tirefe_static_forces("tires.145SR12", coarse, 1, deflections, n, forces, error, sizeof error);
        require_answer(status, error, "static_forces");
        if (status == TIREFE_OK)
          for (size_t k = 0; k < n; ++k) require(std::isfinite(forces[k]), "a static force is not finite");
        continue;
      }
      default: {
        double level = 0.0;
        status = tirefe_road_level(tire, &level);
        require(status == TIREFE_OK && std::isfinite(level) && level < 0.0, "the road level is not below the spindle");
        break;
      }
    }
    require_answer(status, tirefe_message(tire), "call " + std::to_string(op));
  }
  for (tirefe_saved_state* state : saved) require(tirefe_free_state(state) == TIREFE_OK, "a saved state does not free");
  tirefe_revert(tire);
}

}  // namespace tirefe::fuzz
