// Tire property files (tirefe.read_tire / write_tire, docs/tire.md): the shipped 145 SR-12
// sets against their Lua tables, bit-for-bit round trips, the errors with file, line and
// key, and the key table of the docs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "deck_support.hpp"
#include "test_support.hpp"
#include "tire/tire_builder.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe;
using Catch::Matchers::Contains;
using tirefe::testing::replaced;
using tirefe::testing::same_bits;
using tirefe::testing::TempDir;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every parameter model:tire sets, compared bit for bit.
void check_same_parameters(const TireParameters& a, const TireParameters& b) {
  CHECK(a.elements == b.elements);
  const std::pair<const char*, std::pair<double, double>> values[] = {
      {"outer_diameter", {a.outer_diameter, b.outer_diameter}},
      {"rim_diameter", {a.rim_diameter, b.rim_diameter}},
      {"tread_width", {a.tread_width, b.tread_width}},
      {"pressure", {a.pressure, b.pressure}},
      {"tread_EA", {a.tread.axial_stiffness, b.tread.axial_stiffness}},
      {"tread_GA", {a.tread.shear_stiffness, b.tread.shear_stiffness}},
      {"tread_EI", {a.tread.bending_stiffness, b.tread.bending_stiffness}},
      {"tread_mass_per_length", {a.tread.mass_per_length, b.tread.mass_per_length}},
      {"tread_rotary_inertia_per_length", {a.tread.rotary_inertia_per_length, b.tread.rotary_inertia_per_length}},
      {"tread_curvature_damping", {a.tread.curvature_damping, b.tread.curvature_damping}},
      {"sidewall_length", {a.sidewall.cord_length, b.sidewall.cord_length}},
      {"k_sw", {a.sidewall.bending_stiffness, b.sidewall.bending_stiffness}},
      {"k_sw_sign", {a.sidewall.bending_sign, b.sidewall.bending_sign}},
      {"k_gamma", {a.sidewall.shear_stiffness, b.sidewall.shear_stiffness}},
      {"sidewall_radial_damping", {a.sidewall.radial_damping, b.sidewall.radial_damping}},
      {"sidewall_circumferential_damping", {a.sidewall.circumferential_damping, b.sidewall.circumferential_damping}},
      {"rim_mass", {a.rim_mass, b.rim_mass}},
      {"rim_rotary_inertia", {a.rim_rotary_inertia, b.rim_rotary_inertia}},
      {"tread_layer_radial_stiffness", {a.tread_layer.radial_stiffness, b.tread_layer.radial_stiffness}},
      {"tread_layer_circumferential_stiffness",
       {a.tread_layer.circumferential_stiffness, b.tread_layer.circumferential_stiffness}},
      {"tread_layer_mass_per_length", {a.tread_layer.mass_per_length, b.tread_layer.mass_per_length}},
      {"tread_layer_radial_damping", {a.tread_layer.radial_damping, b.tread_layer.radial_damping}},
      {"tread_layer_circumferential_damping",
       {a.tread_layer.circumferential_damping, b.tread_layer.circumferential_damping}},
      {"x", {a.centre.x(), b.centre.x()}},
      {"y", {a.centre.y(), b.centre.y()}}};
  for (const auto& [name, pair] : values) {
    INFO(name << ": " << pair.first << " vs " << pair.second);
    CHECK(same_bits(pair.first, pair.second));
  }
}

const std::string kShippedSets[][2] = {{"tires.145SR12", "inputs/tires/145SR12.tir"},
                                       {"tires.145SR12_tread_layer", "inputs/tires/145SR12_tread_layer.tir"}};

}  // namespace

TEST_CASE("the shipped 145 SR-12 property files hold exactly the parameters of the Lua sets", "[tire][tire_file]") {
  for (const auto& [module, file] : kShippedSets) {
    INFO(file);
    check_same_parameters(macros::load_tire_parameters(module),
                          macros::load_tire_parameters(std::string(TIREFE_SOURCE_DIR) + "/" + file));
  }
  // The layered set really differs from the paper's, so the comparison can fail.
  CHECK(macros::load_tire_parameters(std::string(TIREFE_SOURCE_DIR) + "/inputs/tires/145SR12_tread_layer.tir")
            .tread_layer.radial_stiffness == 1.0e7);
}

TEST_CASE("write_tire then read_tire gives back every parameter bit for bit", "[tire][tire_file]") {
  TempDir folder;
  SECTION("the shipped sets, written again, read back as the Lua tables") {
    const std::string deck = folder.write("export.lua", R"(
tirefe.write_tire{ file = "a.tir", parameters = require("tires.145SR12"), comments = { "the paper's model" } }
tirefe.write_tire{ file = "b.tir", parameters = require("tires.145SR12_tread_layer") }
)");
    const auto run = testing::run_deck_in_process(deck, folder.path("out"));
    REQUIRE(run.error.empty());
    check_same_parameters(macros::load_tire_parameters("tires.145SR12"),
                          macros::load_tire_parameters(folder.path("out/a.tir")));
    check_same_parameters(macros::load_tire_parameters("tires.145SR12_tread_layer"),
                          macros::load_tire_parameters(folder.path("out/b.tir")));
    CHECK_THAT(read_text(folder.path("out/a.tir")), Contains("(COMMENTS)\n{comment_string}\n\"the paper's model\"\n"));
  }
  SECTION("awkward values: the last bit, a third, a subnormal, a negative sign") {
    const std::string deck = folder.write("awkward.lua", R"(
local set = {}
for key, value in pairs(require("tires.145SR12_tread_layer")) do set[key] = value end
set.k_sw = 0.1 + 0.2
set.tread_EI = 1 / 3
set.pressure = 0.208e6 * (1 + 2^-52)
set.tread_curvature_damping = 5e-324
set.k_sw_sign = -1
set.elements = 64
tirefe.write_tire{ file = "awkward.tir", parameters = set }
local back = tirefe.read_tire{ file = "out/awkward.tir" }
local differing, compared = 0, 0
for key, value in pairs(set) do
  compared = compared + 1
  if string.format("%a", back[key]) ~= string.format("%a", value) then
    print(key, value, back[key])
    differing = differing + 1
  end
end
tirefe.check{ name = "keys compared", value = compared, expected = 24 }
tirefe.check{ name = "keys differing in any bit", value = differing, expected = 0 }
)");
    testing::check_deck_passes(deck, folder.path("out"), 2);
  }
}

TEST_CASE("tire property file errors name the deck line, the file, its line and the key", "[tire][tire_file]") {
  TempDir folder;
  const std::string shipped = read_text(std::string(TIREFE_SOURCE_DIR) + "/inputs/tires/145SR12.tir");
  REQUIRE(!shipped.empty());
  const auto line_of = [&](const std::string& text, const std::string& what) {
    const size_t at = text.find(what);
    REQUIRE(at != std::string::npos);
    return std::to_string(1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  };
  struct Case {
    std::string text, message;
  };
  const std::string misspelt = replaced(shipped, "BENDING_STIFFNESS", "BENDING_STIFNESS");
  const std::string section = replaced(shipped, "[TREAD_LAYER]", "[TREAD_LAYR]");
  const std::string twice = replaced(shipped, "[RIM]\n", "[RIM]\nMASS = 3\n");
  const std::string not_number = replaced(shipped, "= 0.11 ", "= 0.11m");
  const std::string negative = replaced(shipped, "= 3000000 ", "= -3000000");
  const std::string fraction = replaced(shipped, "= 100 ", "= 100.5");
  const std::string missing = replaced(shipped, "RIM_RADIUS", "$RIM_RADIUS");
  const std::string format = replaced(shipped, "'TIREFE'", "'PAC2002'");
  const std::string units = replaced(shipped, "'kg'", "'kilo'");
  const std::string nul = replaced(shipped, "= 208000 ", std::string("= 208") + '\0' + "000 ");
  const Case cases[] = {
      {misspelt, "bad.tir:" + line_of(misspelt, "BENDING_STIFNESS") +
                     ": [TREAD] unknown key 'BENDING_STIFNESS' (did you mean 'BENDING_STIFFNESS'?"},
      {section,
       "bad.tir:" + line_of(section, "[TREAD_LAYR]") + ": unknown section [TREAD_LAYR] (did you mean '[TREAD_LAYER]'?"},
      {twice, "bad.tir:" + std::to_string(std::stoi(line_of(twice, "MASS = 3")) + 1) +
                  ": [RIM] MASS is given twice (first at line " + line_of(twice, "MASS = 3") + ")"},
      {not_number, "bad.tir:" + line_of(not_number, "0.11m") + ": [TREAD] WIDTH = 0.11m is not a finite number"},
      {negative, "bad.tir:" + line_of(negative, "-3000000") +
                     ": [TREAD] AXIAL_STIFFNESS: tread_EA must be positive (got -3000000)"},
      {fraction, "bad.tir:" + line_of(fraction, "100.5") + ": [MODEL] ELEMENTS must be a whole number"},
      {missing, "bad.tir:" + line_of(missing, "[DIMENSION]") +
                    ": missing [DIMENSION] RIM_RADIUS (half of rim_diameter: effective rim diameter, a length)"},
      {format, "bad.tir:" + line_of(format, "PAC2002") +
                   ": [MODEL] PROPERTY_FILE_FORMAT = 'PAC2002', but [TREAD] is a section of tirefe's ring tire"},
      {nul, "bad.tir:" + line_of(nul, "INFLPRES") + ": a NUL byte in the line"},
      {units, "bad.tir:" + line_of(units, "'kilo'") + ": [UNITS] MASS = 'kilo' is not a known mass unit"},
  };
  const std::string deck = folder.write("deck.lua", "local x = 1\nlocal tp = tirefe.read_tire{ file = \"bad.tir\" }\n");
  for (const Case& c : cases) {
    folder.write("bad.tir", c.text);
    const auto run = testing::run_deck_in_process(deck, folder.path("out"));
    INFO(c.message);
    CHECK_THAT(run.error, Contains("deck.lua:2: macro 'read_tire': ") && Contains(c.message));
  }
  // The standard [DIMENSION] keys beside the ring's own are taken and not used.
  folder.write("bad.tir", replaced(shipped, "[DIMENSION]\n", "[DIMENSION]\nWIDTH = 0.145\nASPECT_RATIO = 0.82\n"));
  CHECK(testing::run_deck_in_process(deck, folder.path("out")).error.empty());
  const auto missing_file = testing::run_deck_in_process(
      folder.write("none.lua", "tirefe.read_tire{ file = \"none.tir\" }\n"), folder.path("out"));
  CHECK_THAT(missing_file.error, Contains("none.lua:1:") && Contains("none.tir: cannot open the file"));
}

TEST_CASE("write_tire refuses keys that place a tire, and parameter sets model:tire would refuse",
          "[tire][tire_file]") {
  TempDir folder;
  const std::pair<std::string, std::string> cases[] = {
      {"local s = require(\"tires.145SR12\")\ns.x = 1\ntirefe.write_tire{ file = \"t.tir\", parameters = s }\n",
       "place.lua:3: macro 'write_tire': 'parameters' key 'x' places a tire in a model"},
      {"local s = require(\"tires.145SR12\")\ns.tread_EJ = 1\ntirefe.write_tire{ file = \"t.tir\", parameters = s }\n",
       "place.lua:3: macro 'write_tire parameters': unknown key 'tread_EJ' (did you mean 'tread_EI'?"},
      {"tirefe.write_tire{ file = \"t.tir\", parameters = { elements = 10 } }\n",
       "place.lua:1: macro 'write_tire parameters': missing required key 'outer_diameter'"},
  };
  for (const auto& [text, message] : cases) {
    const auto run = testing::run_deck_in_process(folder.write("place.lua", text), folder.path("out"));
    CHECK_THAT(run.error, Contains(message));
  }
}

TEST_CASE("docs/tire.md holds the current key table of tire property files", "[docs][tire_file]") {
  const std::string documented = read_text(std::string(TIREFE_SOURCE_DIR) + "/docs/tire.md");
  CHECK_THAT(documented, Contains(macros::tire_property_file_reference()));
}
