// Tests of the deck sandbox (safe libraries, require, parameters, error locations) and of
// macro argument validation against a MacroSpec.
#include <catch2/catch.hpp>

#include "deck/lua_sandbox.hpp"
#include "macros/macro_spec.hpp"
#include "test_support.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace tirefe::macros;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

using tirefe::testing::TempDir;

const MacroSpec& beam_spec() {
  static const MacroSpec spec{
      "beam",
      "Timoshenko beam ring for the tread band.",
      {{"EA", ValueType::Number, true, "N", "axial stiffness", std::nullopt, Range::Positive},
       {"GA", ValueType::Number, true, "N", "shear stiffness", std::nullopt, Range::Positive},
       {"EI", ValueType::Number, true, "N m^2", "bending stiffness", std::nullopt, Range::Positive},
       {"elements", ValueType::Integer, false, "", "number of elements", "36", Range::Positive},
       {"damping", ValueType::Number, false, "", "damping ratio", "0.02", Range::Fraction01},
       {"integrator",
        ValueType::String,
        false,
        "",
        "time integrator",
        "newmark",
        Range::Any,
        {"newmark", "hht", "static"}},
       {"radii", ValueType::NumberList, false, "m", "layer radii", std::nullopt, Range::Positive},
       {"nodes", ValueType::IntegerList, false, "", "output nodes"},
       {"profile", ValueType::NumberMatrix, false, "m", "cross-section points (y, z)"},
       {"verbose", ValueType::Boolean, false, "", "print progress", "false"},
       {"on_step", ValueType::Function, false, "", "called after each step"}},
      "tirefe.beam{EA = 1e7, GA = 1e5, EI = 12.5}"};
  return spec;
}

struct BeamCall {
  double EI = 0, damping = 0;
  long long elements = 0;
  std::string integrator;
  std::vector<double> radii;
  std::vector<long long> nodes;
  std::vector<std::vector<double>> profile;
  bool verbose = true;
  double callback_result = 0;
};
BeamCall last_beam;

int lua_beam(lua_State* L) {
  const MacroArguments args(L, 1, beam_spec());
  last_beam = BeamCall{};
  last_beam.EI = args.number("EI");
  last_beam.damping = args.number("damping");
  last_beam.elements = args.integer("elements");
  last_beam.integrator = args.string("integrator");
  last_beam.verbose = args.boolean("verbose");
  if (args.has("radii")) last_beam.radii = args.number_list("radii");
  if (args.has("nodes")) last_beam.nodes = args.integer_list("nodes");
  if (args.has("profile")) last_beam.profile = args.number_matrix("profile");
  if (args.has("on_step")) {
    args.push_value("on_step");
    lua_call(L, 0, 1);
    last_beam.callback_result = lua_tonumber(L, -1);
  }
  return 0;
}

int lua_read_absent_list(lua_State* L) {  // a binding bug: reads an optional key with no default
  const MacroArguments args(L, 1, beam_spec());
  return static_cast<int>(args.number_list("radii").size());
}

int destroyed = 0;
struct Tracker {
  ~Tracker() { ++destroyed; }
};
int lua_throws(lua_State*) {
  Tracker tracker;
  throw std::runtime_error("tread mesh has no elements");
}
int lua_raises(lua_State* L) {
  Tracker tracker;
  luaL_error(L, "contact search failed");
  return 0;
}

void bind_test_functions(LuaSandbox& sandbox) {
  sandbox.register_function("beam", protected_call<lua_beam>);
  sandbox.register_function("read_absent_list", protected_call<lua_read_absent_list>);
  sandbox.register_function("throws", protected_call<lua_throws>);
  sandbox.register_function("raises", protected_call<lua_raises>);
}

// Runs a deck and returns the DeckError message ("" if the deck ran).
std::string deck_error(LuaSandbox& sandbox, const std::string& path,
                       const std::map<std::string, std::string>& overrides = {}) {
  try {
    sandbox.run_file(path, overrides);
  } catch (const DeckError& e) {
    return e.what();
  }
  return "";
}

int global_type(lua_State* L, const char* name) {
  const int type = lua_getglobal(L, name);
  lua_pop(L, 1);
  return type;
}
double global_number(lua_State* L, const char* name) {
  lua_getglobal(L, name);
  const double value = lua_tonumber(L, -1);
  lua_pop(L, 1);
  return value;
}
bool global_boolean(lua_State* L, const char* name) {
  lua_getglobal(L, name);
  const bool value = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return value;
}

}  // namespace

TEST_CASE("macro arguments are validated with the deck line and key in the message", "[lua][macros]") {
  struct Case {
    std::string call, expected;
  };
  const std::vector<Case> cases{
      {"tirefe.beam(5)",
       "macro 'beam' expects a table of named arguments, e.g. tirefe.beam{EA = 1e7, GA = 1e5, EI = 12.5}"},
      {"tirefe.beam{1}", "macro 'beam' takes named arguments only, got a positional number 1"},
      {"tirefe.beam{EA = 1, GA = 1, EJ = 1}",
       "macro 'beam': unknown key 'EJ' (did you mean 'EI'?; known keys: EA, GA, EI, elements"},
      {"tirefe.beam{EA = 1, GA = 1, zzz = 1, EI = 1}", "macro 'beam': unknown key 'zzz' (known keys: EA, GA, EI"},
      {"tirefe.beam{EA = 1, GA = 1}", "macro 'beam': missing required key 'EI' (bending stiffness, N m^2)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 'abc'}", "macro 'beam': key 'EI' must be a number, got string \"abc\""},
      {"tirefe.beam{EA = 1, GA = 1, EI = 0/0}", "macro 'beam': key 'EI' is not a finite number"},
      {"tirefe.beam{EA = 1, GA = 1, EI = math.huge}", "macro 'beam': key 'EI' is not a finite number"},
      {"tirefe.beam{EA = 1, GA = 1, EI = -3}", "macro 'beam': key 'EI' must be positive (got -3)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, elements = 2.5}", "key 'elements' must be an integer, got number 2.5"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, elements = 2^32 + 24}",  // would wrap to 24 in an int
       "key 'elements' must be an integer from 1 to 2147483647 (got number 4294967320)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, elements = 2147483648}",
       "key 'elements' must be an integer from 1 to 2147483647 (got number 2147483648)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, elements = 0}", "key 'elements' must be positive (got 0)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, nodes = {1, -2^31 - 1}}",
       "key 'nodes' entry 2 must be an integer from -2147483648 to 2147483647 (got number -2147483649)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, elements = 2^63}",
       "key 'elements' must be an integer, got number 9.2233720368548e+18"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, damping = 1.5}", "key 'damping' must be between 0 and 1 (got 1.5)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, integrator = 'newmak'}",
       "key 'integrator' must be one of newmark, hht, static (got 'newmak')"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, verbose = 1}", "key 'verbose' must be a boolean, got number 1"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, radii = {0.3, 'x'}}",
       "key 'radii' entry 2 must be a number, got string \"x\""},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, radii = {0.3, -1}}", "key 'radii' entry 2 must be positive (got -1)"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, radii = {0.3, foo = 1}}",
       "key 'radii' must be a list of numbers {a, b, ...}, found key string \"foo\""},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, nodes = {1, 2.5}}",
       "key 'nodes' entry 2 must be an integer, got number 2.5"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, profile = {{0, 1}, {0, 1, 2}}}",
       "key 'profile' row 2 has 3 entries, expected 2 like row 1"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, profile = {{0, 1}, 5}}",
       "key 'profile' row 2 must be a list of numbers, got number 5"},
      {"tirefe.beam{EA = 1, GA = 1, EI = 1, on_step = 3}", "key 'on_step' must be a function, got number 3"},
      {"tirefe.read_absent_list{EA = 1, GA = 1, EI = 1}",
       "macro 'beam': key 'radii' was not given and has no usable default"},
  };
  TempDir dir;
  for (const auto& c : cases) {
    LuaSandbox sandbox("");
    bind_test_functions(sandbox);
    const std::string deck = dir.write("deck.lua", "-- ring model\nlocal ok = true\n" + c.call + "\n");
    INFO(c.call);
    const std::string message = deck_error(sandbox, deck);
    CHECK_THAT(message, StartsWith(deck + ":3: ") && Contains(c.expected));
  }
}

TEST_CASE("valid macro arguments are read with their defaults", "[lua][macros]") {
  TempDir dir;
  LuaSandbox sandbox("");
  bind_test_functions(sandbox);
  const std::string deck = dir.write("deck.lua", R"(
tirefe.beam{EA = 1e7, GA = 1e5, EI = 12.5, elements = 1e2, radii = {0.30, 0.31}, nodes = {1, 5},
            profile = {{0, 0.1}, {0.05, 0.12}}, on_step = function() return 42 end}
)");
  sandbox.run_file(deck);
  CHECK(last_beam.EI == 12.5);
  CHECK(last_beam.elements == 100);  // integral float accepted as integer
  CHECK(last_beam.damping == 0.02);  // spec default
  CHECK(last_beam.integrator == "newmark");
  CHECK_FALSE(last_beam.verbose);
  CHECK(last_beam.radii == std::vector<double>{0.30, 0.31});
  CHECK(last_beam.nodes == std::vector<long long>{1, 5});
  CHECK(last_beam.profile == std::vector<std::vector<double>>{{0, 0.1}, {0.05, 0.12}});
  CHECK(last_beam.callback_result == 42);
  CHECK(sandbox.deck_text().find("tirefe.beam{EA = 1e7") != std::string::npos);
  CHECK(sandbox.deck_path() == deck);

  // The ends of an int are accepted (2^31 - 1 as an integral float too).
  sandbox.run_file(dir.write("ends.lua",
                             "tirefe.beam{EA = 1, GA = 1, EI = 1, elements = 2^31 - 1, "
                             "nodes = {-2147483648, 2147483647}}\n"));
  CHECK(last_beam.elements == 2147483647);
  CHECK(last_beam.nodes == std::vector<long long>{-2147483648LL, 2147483647});
}

TEST_CASE("the deck sandbox offers only safe libraries and text-only loading", "[lua][sandbox]") {
  TempDir dir;
  LuaSandbox sandbox("");
  const std::string deck = dir.write("deck.lua", R"(
local bin = string.dump(function() return 1 end)
local f, err = load(bin)
binary_refused = f == nil and err:find("binary") ~= nil
binary_mode_refused = load(bin, "chunk", "b") == nil
text_result = load("return 20 + 22")()
env_result = load("return answer", "chunk", "t", {answer = 7})()
os_execute_nil = os.execute == nil and os.remove == nil and os.exit == nil
clock_ok = type(os.clock()) == "number" and type(os.date()) == "string"
libs_ok = string and table and math and utf8 and coroutine and true
)");
  sandbox.run_file(deck);
  for (const char* name : {"io", "debug", "dofile", "loadfile", "package"}) {
    INFO(name);
    CHECK(global_type(sandbox.state(), name) == LUA_TNIL);
  }
  CHECK(global_boolean(sandbox.state(), "binary_refused"));
  CHECK(global_boolean(sandbox.state(), "binary_mode_refused"));
  CHECK(global_number(sandbox.state(), "text_result") == 42);
  CHECK(global_number(sandbox.state(), "env_result") == 7);
  CHECK(global_boolean(sandbox.state(), "os_execute_nil"));
  CHECK(global_boolean(sandbox.state(), "clock_ok"));
  CHECK(global_boolean(sandbox.state(), "libs_ok"));
}

TEST_CASE("deck load and runtime errors name the deck file and line", "[lua][sandbox]") {
  TempDir dir;
  LuaSandbox sandbox("");

  SECTION("syntax error") {
    const std::string deck = dir.write("syntax.lua", "x = 1\ny = = 2\n");
    CHECK_THAT(deck_error(sandbox, deck), StartsWith(deck + ":2: ") && Contains("unexpected symbol"));
  }
  SECTION("runtime error, with the traceback kept apart") {
    const std::string deck = dir.write("runtime.lua", "local t = nil\n\nprint(t.x)\n");
    const std::string message = deck_error(sandbox, deck);
    CHECK_THAT(message, StartsWith(deck + ":3: ") && Contains("attempt to index"));
    CHECK_THAT(message, !Contains("stack traceback"));
    CHECK_THAT(sandbox.last_traceback(), Contains("stack traceback"));
  }
  SECTION("error(msg, 2) points at the caller's deck line") {
    const std::string deck = dir.write("level.lua", "local function check(x)\n  error('bad x', 2)\nend\ncheck(1)\n");
    CHECK_THAT(deck_error(sandbox, deck), StartsWith(deck + ":4: bad x"));
  }
  SECTION("binary chunk") {
    lua_State* plain = luaL_newstate();
    REQUIRE(luaL_loadstring(plain, "x = 1") == LUA_OK);
    std::string bytes;
    lua_dump(
        plain,
        [](lua_State*, const void* p, size_t n, void* out) {
          static_cast<std::string*>(out)->append(static_cast<const char*>(p), n);
          return 0;
        },
        &bytes, 0);
    lua_close(plain);
    const std::string deck = dir.write("binary.lua", bytes);
    CHECK_THAT(deck_error(sandbox, deck), StartsWith(deck + ": ") && Contains("binary"));
  }
  SECTION("missing deck") {
    CHECK_THAT(deck_error(sandbox, dir.path("none.lua")), StartsWith(dir.path("none.lua") + ": cannot open"));
  }
}

TEST_CASE("require searches beside the deck, then lua_dir, and caches modules", "[lua][sandbox]") {
  TempDir dir;
  const std::string helper = dir.write("deck/helper.lua", R"(load_count = (load_count or 0) + 1
local M = {}
function M.twice(x) return 2 * x end
function M.check_width(w)
  if w <= 0 then error("tread width must be positive") end
end
function M.make_beam() tirefe.beam{EA = 1, GA = 1, EJ = 1} end
return M
)");
  dir.write("deck/common.lua", "return { where = 'deck' }\n");
  dir.write("lib/common.lua", "return { where = 'lib' }\n");
  dir.write("lib/shapes/circle.lua", "return { area = function(r) return math.pi * r * r end }\n");
  dir.write("lib/tirelib/init.lua", "return { name = 'tirelib' }\n");
  LuaSandbox sandbox(dir.path("lib"));
  bind_test_functions(sandbox);

  SECTION("found and cached") {
    const std::string deck = dir.write("deck/deck.lua", R"(
local a = require("helper")
local b = require("helper")
same_module = rawequal(a, b)
doubled = a.twice(21)
circle = require("shapes.circle").area(1)
tirelib = require("tirelib").name == "tirelib"
common_from_deck = require("common").where == "deck"
)");
    sandbox.run_file(deck);
    CHECK(global_number(sandbox.state(), "load_count") == 1);
    CHECK(global_boolean(sandbox.state(), "same_module"));
    CHECK(global_number(sandbox.state(), "doubled") == 42);
    CHECK(global_number(sandbox.state(), "circle") == Approx(3.14159265358979));
    CHECK(global_boolean(sandbox.state(), "tirelib"));
    CHECK(global_boolean(sandbox.state(), "common_from_deck"));
  }
  SECTION("missing module lists the searched paths") {
    const std::string deck = dir.write("deck/deck.lua", "\nrequire('nope.sub')\n");
    const std::string message = deck_error(sandbox, deck);
    CHECK_THAT(message, StartsWith(deck + ":2: module 'nope.sub' not found; searched: "));
    for (const char* base : {"deck", "lib"}) {
      CHECK_THAT(message, Contains((fs::path(dir.path(base)) / "nope/sub.lua").string()));
      CHECK_THAT(message, Contains((fs::path(dir.path(base)) / "nope/sub/init.lua").string()));
    }
  }
  SECTION("invalid module name") {
    const std::string deck = dir.write("deck/deck.lua", "require('../secret')\n");
    CHECK_THAT(deck_error(sandbox, deck), StartsWith(deck + ":1: require: invalid module name"));
  }
  SECTION("errors inside a helper module name the deck line") {
    const std::string deck = dir.write("deck/deck.lua", "local h = require('helper')\nh.twice(1)\nh.check_width(-1)\n");
    const std::string message = deck_error(sandbox, deck);
    CHECK_THAT(message, StartsWith(deck + ":3: tread width must be positive (raised at " + helper + ":5)"));
  }
  SECTION("a macro called from a helper module reports the deck line") {
    const std::string deck = dir.write("deck/deck.lua", "local h = require('helper')\n\nh.make_beam()\n");
    CHECK_THAT(deck_error(sandbox, deck), StartsWith(deck + ":3: macro 'beam': unknown key 'EJ'"));
  }
}

TEST_CASE("require hands each caller its own copy of a parameter table", "[lua][sandbox][require]") {
  TempDir dir;
  dir.write("lib/tires/set.lua", R"(load_count = (load_count or 0) + 1
return { pressure = 2e5, layer = { stiffness = 1e7 }, names = { "belt", "tread" } }
)");
  LuaSandbox sandbox(dir.path("lib"));
  bind_test_functions(sandbox);
  const std::string deck = dir.write("deck/deck.lua", R"(
local first = require("tires.set")
first.pressure = 1
first.layer.stiffness = 2
first.names[1] = "ply"
first.y = 0.5
local second = require("tires.set")
pressure = second.pressure
stiffness = second.layer.stiffness
first_name_kept = second.names[1] == "belt"
has_y = second.y ~= nil
distinct = not rawequal(first, second) and not rawequal(first.layer, second.layer)
)");
  sandbox.run_file(deck);
  CHECK(global_number(sandbox.state(), "load_count") == 1);  // loaded once, copied per require
  CHECK(global_number(sandbox.state(), "pressure") == 2e5);
  CHECK(global_number(sandbox.state(), "stiffness") == 1e7);
  CHECK(global_boolean(sandbox.state(), "first_name_kept"));
  CHECK_FALSE(global_boolean(sandbox.state(), "has_y"));
  CHECK(global_boolean(sandbox.state(), "distinct"));
}

TEST_CASE("protected_call turns C++ exceptions into deck errors and unwinds C++ frames", "[lua][sandbox]") {
  TempDir dir;
  LuaSandbox sandbox("");
  bind_test_functions(sandbox);

  SECTION("std::exception") {
    destroyed = 0;
    const std::string deck = dir.write("deck.lua", "local x = 1\ntirefe.throws()\n");
    CHECK(deck_error(sandbox, deck) == deck + ":2: tread mesh has no elements");
    CHECK(destroyed == 1);
  }
  SECTION("a Lua error raised from C++ runs destructors (C++ build of Lua)") {
    destroyed = 0;
    const std::string deck = dir.write("deck.lua", "\n\ntirefe.raises()\n");
    CHECK(deck_error(sandbox, deck) == deck + ":3: contact search failed");
    CHECK(destroyed == 1);
  }
}

TEST_CASE("tirefe.parameters applies typed command-line overrides", "[lua][parameters]") {
  TempDir dir;
  LuaSandbox sandbox("");
  const std::string deck = dir.write(
      "deck.lua", R"(local defaults = { speed_kmh = 51.3, elements = 100, integrator = "newmark", contact = true }
local p = tirefe.parameters(defaults)
speed, elements, integrator, contact = p.speed_kmh, p.elements, p.integrator, p.contact
elements_is_integer = math.type(p.elements) == "integer"
speed_is_float = math.type(p.speed_kmh) == "float"
defaults_untouched = defaults.speed_kmh == 51.3 and p ~= defaults
)");
  lua_State* L = sandbox.state();
  const auto global_string = [&](const char* name) {
    lua_getglobal(L, name);
    std::string value = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
    lua_pop(L, 1);
    return value;
  };

  SECTION("defaults") {
    sandbox.run_file(deck);
    CHECK(global_number(L, "speed") == 51.3);
    CHECK(global_number(L, "elements") == 100);
    CHECK(global_string("integrator") == "newmark");
    CHECK(global_boolean(L, "contact"));
  }
  SECTION("overrides of each type") {
    sandbox.run_file(deck, {{"speed_kmh", "80"}, {"elements", "200"}, {"integrator", "hht"}, {"contact", "false"}});
    CHECK(global_number(L, "speed") == 80);
    CHECK(global_boolean(L, "speed_is_float"));
    CHECK(global_number(L, "elements") == 200);
    CHECK(global_boolean(L, "elements_is_integer"));
    CHECK(global_string("integrator") == "hht");
    CHECK(global_type(L, "contact") == LUA_TBOOLEAN);
    CHECK_FALSE(global_boolean(L, "contact"));
    CHECK(global_boolean(L, "defaults_untouched"));
  }
  SECTION("errors") {
    CHECK_THAT(deck_error(sandbox, deck, {{"tread", "3"}}),
               StartsWith(deck + ":2: command-line parameter 'tread' is not declared by the deck") &&
                   Contains("declared: contact, elements, integrator, speed_kmh"));
    CHECK_THAT(deck_error(sandbox, deck, {{"speed_kmh", "fast"}}),
               StartsWith(deck + ":2: command-line parameter 'speed_kmh=fast' must be a number"));
    CHECK_THAT(deck_error(sandbox, deck, {{"elements", "2.5"}}), Contains("'elements=2.5' must be an integer"));
    CHECK_THAT(deck_error(sandbox, deck, {{"contact", "maybe"}}), Contains("'contact=maybe' must be true or false"));
  }
  SECTION("override for a deck that declares no parameters") {
    const std::string plain = dir.write("plain.lua", "x = 1\n");
    CHECK(
        deck_error(sandbox, plain, {{"speed_kmh", "80"}}) ==
        plain +
            ": command-line parameter 'speed_kmh' is not declared by the deck (declare it with tirefe.parameters{...})");
  }
}

TEST_CASE("markdown_reference documents every macro and key", "[lua][macros]") {
  const MacroSpec solve{"solve",
                        "Advance the solution in time.",
                        {{"dt", ValueType::Number, true, "s", "time step", std::nullopt, Range::Positive}},
                        "tirefe.solve{dt = 1e-4}"};
  const std::string doc = markdown_reference({beam_spec(), solve});
  for (const std::string name : {"## beam", "## solve", "tirefe.solve{dt = 1e-4}"}) CHECK_THAT(doc, Contains(name));
  for (const auto* spec : {&beam_spec(), &solve})
    for (const auto& p : spec->parameters) CHECK_THAT(doc, Contains("| `" + p.key + "` |"));
  CHECK_THAT(doc, Contains("| `EI` | number > 0 | N m^2 | required | bending stiffness |"));
  CHECK_THAT(doc, Contains("| `elements` | integer > 0 |  | default `36` |"));
  CHECK_THAT(doc, Contains("One of: `newmark`, `hht`, `static`."));
}
