// Standard tire property files (src/formats/mf_tire_file.hpp, docs/mf_tire_files.md): the
// public MF-Tyre files of inputs/tires/ read as published, what they state, the ring built
// from them, the errors, and the fit of inputs/identify_tir.lua.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

#include "deck_support.hpp"
#include "formats/mf_tire_file.hpp"
#include "formats/teim_orbit.hpp"
#include "test_support.hpp"
#include "tire/tire_builder.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe;
using Catch::Matchers::Contains;
using tirefe::testing::replaced;
using tirefe::testing::TempDir;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string shipped(const std::string& name) { return std::string(TIREFE_SOURCE_DIR) + "/inputs/tires/" + name; }

MfTireFile read_standard(const std::string& path) {
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::read(path);
  formats::TeimOrbitReader reader(file, "tir");
  return MfTireFile::read(file, reader);
}

MfTireFile parse_standard(const std::string& text) {
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(text, "t.tir");
  formats::TeimOrbitReader reader(file, "tir");
  return MfTireFile::read(file, reader);
}

std::map<std::string, double> ring_of(const MfTireFile& tire, std::optional<double> pressure = std::nullopt,
                                      std::optional<double> tread_width = std::nullopt) {
  std::map<std::string, double> out;
  for (const RingParameter& parameter : ring_parameters(tire, pressure, tread_width))
    out[parameter.key] = parameter.value;
  return out;
}

const std::string kMinimal =
    "[UNITS]\nLENGTH = 'meter'\nFORCE = 'newton'\nANGLE = 'radians'\nMASS = 'kg'\nTIME = 'second'\n"
    "[DIMENSION]\nUNLOADED_RADIUS = 0.3\nWIDTH = 0.2\nRIM_RADIUS = 0.2\n"
    "[OPERATING_CONDITIONS]\nINFLPRES = 2e5\n[VERTICAL]\nFNOMIN = 4000\nVERTICAL_STIFFNESS = 2e5\n";

}  // namespace

TEST_CASE("public MF-Tyre files are read as published: no header, CRLF, blank values, [SHAPE] tables",
          "[tire][tire_file][mf]") {
  SECTION("Project Chrono's HMMWV tire: no [MDI_HEADER], PRESSURE unit, [TIRE_CONDITIONS], LFZO and LCZ") {
    const MfTireFile tire = read_standard(shipped("HMMWV_Pac02Tire.tir"));
    CHECK(tire.format == "PAC2002");
    CHECK(tire.unloaded_radius == 0.4699);
    CHECK(*tire.rim_radius == 0.20955);
    CHECK(*tire.inflation_pressure == 800000.0);
    CHECK(*tire.nominal_load == Approx(35000 * 0.580904846).epsilon(1e-15));  // FNOMIN scaled by LFZO
    CHECK(*tire.vertical_stiffness == Approx(1e6 * 0.4419).epsilon(1e-15));   // by LCZ
    CHECK_FALSE(tire.belt_mass);
    CHECK(*tire.pac2002_belt_mass == 0.0);  // MBELT = 0: not given
    CHECK(*tire.stated_deflection(*tire.nominal_load, 8e5) == Approx(35000 * 0.580904846 / 441900.0).epsilon(1e-14));
  }
  SECTION("the VW microbus tire: [SHAPE] with its column line, MBELT, no pressure but read_tire's") {
    const MfTireFile tire = read_standard(shipped("mf_185_80R14.tir"));
    CHECK(*tire.pac2002_belt_mass == 3.5);
    CHECK_FALSE(tire.inflation_pressure);
    CHECK_THROWS_WITH(
        ring_parameters(tire, std::nullopt),
        Contains("mf_185_80R14.tir: the file states no inflation pressure") && Contains("give read_tire a 'pressure'"));
    const auto ring = ring_of(tire, 190e3);
    CHECK(ring.at("pressure") == 190e3);
    CHECK(ring.at("tread_mass_per_length") == Approx(3.5 / (2 * kPi * 0.376)).epsilon(1e-15));
    CHECK(ring.at("outer_diameter") == 0.752);
    CHECK(ring.at("tread_width") == Approx(0.75 * 0.185).epsilon(1e-15));
  }
  SECTION("the FED-alpha truck tire: [SHAPE] without column names, a [DEFLECTION_LOAD_CURVE], a vendor section") {
    const MfTireFile tire = read_standard(shipped("335_65R22_5_G275MSA_60psi.tir"));
    REQUIRE(tire.deflection_load.size() == 21);
    CHECK(tire.deflection_load[8] == Eigen::Vector2d(0.040, 21124.160));
    // FNOMIN = 21674 N lies between the rows at 40 and 45 mm: linear there.
    const double deflection = 0.040 + 0.005 * (21674 - 21124.160) / (24269.190 - 21124.160);
    CHECK(*tire.stated_deflection(21674, 0.0) == Approx(deflection).epsilon(1e-14));
    CHECK(*tire.stated_load(0.0125, 0.0) == Approx(0.5 * (4242.260 + 6688.460)).epsilon(1e-14));
  }
  SECTION("ExternData's MF 6.1 sample: FITTYP only, [INERTIA], the law's QFZ2 in [LOADED_RADIUS_COEFFICIENTS]") {
    const MfTireFile tire = read_standard(shipped("sample_mf61.tir"));
    CHECK(tire.format == "FITTYP 61");
    CHECK(*tire.mass == 9.3);
    CHECK(*tire.belt_mass == 7.247);
    CHECK(*tire.belt_polar_inertia == 0.55);
    CHECK(*tire.quadratic_stiffness == 15.4);
    // F(d) = Cz d + Q_FZ2 FNOMIN (d / R0)^2 at FNOMIN.
    const double d = *tire.stated_deflection(4000, 2e5);
    CHECK(209651 * d + 15.4 * 4000 * (d / 0.3135) * (d / 0.3135) == Approx(4000).epsilon(1e-13));
    const auto ring = ring_of(tire);
    CHECK(ring.at("rim_mass") == Approx(9.3 - 7.247).epsilon(1e-15));
    CHECK(ring.at("rim_rotary_inertia") == Approx(0.8 - 0.55).epsilon(1e-15));
    CHECK(ring.at("tread_mass_per_length") == Approx(7.247 / (2 * kPi * 0.3135)).epsilon(1e-15));
  }
  SECTION("PFZ1 scales the stated stiffness with the pressure: (1 + PFZ1 (p - NOMPRES) / NOMPRES)") {
    const MfTireFile tire = read_standard(shipped("mf_swift_205_60R15.tir"));
    CHECK(*tire.stated_load(0.01, 2.2e5) / *tire.stated_load(0.01, 2e5) == Approx(1 + 0.7098 * 0.1).epsilon(1e-14));
    CHECK(*tire.longitudinal_frequency == 77.0);
    CHECK(*tire.windup_damping == 0.05);
  }
}

TEST_CASE("the ring of a standard file takes what the file does not state from the 145 SR-12 set per tread width",
          "[tire][tire_file][mf]") {
  // A section width whose three quarters are the set's 0.110 m: the estimates are the set's values.
  const std::string text =
      replaced(replaced(replaced(kMinimal, "WIDTH = 0.2", "WIDTH = " + formats::round_trip_number(0.110 / 0.75)),
                        "UNLOADED_RADIUS = 0.3", "UNLOADED_RADIUS = 0.2715"),
               "RIM_RADIUS = 0.2", "RIM_RADIUS = 0.1524");
  const auto ring = ring_of(parse_standard(text));
  const TireParameters set = macros::load_tire_parameters("tires.145SR12");
  CHECK(ring.at("tread_width") == Approx(set.tread_width).epsilon(1e-12));
  CHECK(ring.at("tread_EA") == Approx(set.tread.axial_stiffness).epsilon(1e-12));
  CHECK(ring.at("tread_GA") == Approx(set.tread.shear_stiffness).epsilon(1e-12));
  CHECK(ring.at("tread_EI") == Approx(set.tread.bending_stiffness).epsilon(1e-12));
  CHECK(ring.at("tread_mass_per_length") == Approx(set.tread.mass_per_length).epsilon(1e-12));
  CHECK(ring.at("tread_rotary_inertia_per_length") == Approx(set.tread.rotary_inertia_per_length).epsilon(1e-12));
  CHECK(ring.at("k_gamma") == Approx(set.sidewall.shear_stiffness).epsilon(1e-12));
  CHECK(ring.at("sidewall_radial_damping") == Approx(set.sidewall.radial_damping).epsilon(1e-12));
  // The sidewall rule (the membranes carry 3/4 of p w) gives back the set's 0.140 m cord.
  CHECK(ring.at("sidewall_length") == Approx(set.sidewall.cord_length).epsilon(0.003));
}

TEST_CASE("standard tire file errors name the file, the line and what to fix", "[tire][tire_file][mf]") {
  const std::pair<std::string, std::string> cases[] = {
      {replaced(kMinimal, "VERTICAL_STIFFNESS", "VERTICAL_STIFNESS"),
       "t.tir:15: [VERTICAL] unknown key 'VERTICAL_STIFNESS' (did you mean 'VERTICAL_STIFFNESS'? tirefe reads"},
      {replaced(kMinimal, "UNLOADED_RADIUS = 0.3\n", ""), "t.tir:7: missing [DIMENSION] UNLOADED_RADIUS"},
      {replaced(kMinimal, "UNLOADED_RADIUS = 0.3", "UNLOADED_RADIUS ="),
       "t.tir:8: [DIMENSION] UNLOADED_RADIUS has no value"},
      {replaced(kMinimal, "RIM_RADIUS = 0.2", "RIM_RADIUS = 0.4"),
       "t.tir:10: [DIMENSION] RIM_RADIUS must be below UNLOADED_RADIUS"},
      {replaced(kMinimal, "FNOMIN = 4000", "FNOMIN = -4000"), "t.tir:14: [VERTICAL] FNOMIN must be positive"},
      {kMinimal + "[DEFLECTION_LOAD_CURVE]\n0 0\n0.01 1000\n0.02 900\n",
       "t.tir:19: [DEFLECTION_LOAD_CURVE]: the deflection and the load must both rise"},
      {kMinimal + "[DEFLECTION_LOAD_CURVE]\n0 0 0\n", "t.tir:17: [DEFLECTION_LOAD_CURVE] row has 3 values"},
      {kMinimal + "[SCALING_COEFFICIENTS]\nLCZ = 0\n", "t.tir:17: [SCALING_COEFFICIENTS] LCZ must be positive"},
  };
  for (const auto& [text, message] : cases) {
    INFO(text);
    CHECK_THROWS_WITH(parse_standard(text), Contains(message));
  }
  CHECK_THROWS_WITH(ring_parameters(parse_standard(replaced(kMinimal, "WIDTH = 0.2", "WIDTH =")), std::nullopt),
                    Contains("t.tir:7: no value of [DIMENSION] WIDTH") && Contains("or read_tire a 'tread_width'"));
  // With a tread width given, the section width is taken as 4/3 of it.
  const auto narrow = ring_of(parse_standard(replaced(kMinimal, "WIDTH = 0.2", "WIDTH =")), std::nullopt, 0.15);
  CHECK(narrow.at("tread_width") == 0.15);
  CHECK(narrow.at("tread_EA") == Approx(ring_of(parse_standard(kMinimal)).at("tread_EA")).epsilon(1e-15));
  // Keys and sections of the Magic Formula's force model are passed over, misspelt or not.
  CHECK_NOTHROW(parse_standard(kMinimal + "[LATERAL_COEFFICIENTS]\nPCY1 = 1.3\nPCY2 =\nXYZ = 'a'\n[VENDOR]\nA = 1\n"));
}

TEST_CASE("read_tire builds a tire from a standard file and returns what it states", "[tire][tire_file][mf]") {
  TempDir folder;
  const std::string deck = folder.write("read.lua", R"(
local tp, stated = tirefe.read_tire{ file = ")" + shipped("335_65R22_5_G275MSA_60psi.tir") +
                                                        R"(", pressure = 413685 }
tirefe.check{ name = "pressure", value = tp.pressure, expected = 413685 }
tirefe.check{ name = "stated stiffness", value = stated.vertical_stiffness, expected = 530261.9, relative = 1e-6 }
tirefe.check{ name = "law", value = stated.vertical_law == "DEFLECTION_LOAD_CURVE" and 1 or 0, expected = 1 }
tirefe.check{ name = "origin", value = stated.origins.rim_diameter == "2 [DIMENSION] RIM_RADIUS" and 1 or 0,
              expected = 1 }
local model = tirefe.model{}
tirefe.check{ name = "tread nodes", value = #model:tire(tp).tread, expected = 100 }
local narrow = tirefe.read_tire{ file = stated.file, pressure = 413685, tread_width = 0.1 }
tirefe.check{ name = "tread width", value = narrow.tread_width, expected = 0.1 }
tirefe.check{ name = "longer sidewall", value = narrow.sidewall_length > tp.sidewall_length and 1 or 0, expected = 1 }
)");
  testing::check_deck_passes(deck, folder.path("out"), 7);
  const auto own = testing::run_deck_in_process(
      folder.write("own.lua", "tirefe.read_tire{ file = \"" + shipped("145SR12.tir") + "\", tread_width = 0.1 }\n"),
      folder.path("out"));
  CHECK_THAT(own.error, Contains("'tread_width' applies to a standard file"));
  // Hosts (the C API, the FMU) load a standard file the same way, as the unfitted ring.
  CHECK(macros::load_tire_parameters(shipped("HMMWV_Pac02Tire.tir")).outer_diameter == 2 * 0.4699);
}

TEST_CASE("inputs/identify_tir.lua: rings fitted to five standard files reproduce their stiffness and modes",
          "[tire][tire_file][mf][fit][decks]") {
  TempDir folder;
  testing::check_deck_passes(std::string(TIREFE_SOURCE_DIR) + "/inputs/identify_tir.lua", folder.path("out"), 34);
  // The fitted rings are written as tirefe's own files: they read back.
  CHECK(macros::load_tire_parameters(folder.path("out/mf_swift_205_60R15_ring.tir")).outer_diameter == 0.627);
}

TEST_CASE("docs/mf_tire_files.md's table of the fitted rings holds the numbers inputs/identify_tir.lua checks",
          "[docs][tire_file][mf]") {
  const auto text_of = [](const std::string& path) {
    std::ifstream in(std::string(TIREFE_SOURCE_DIR) + "/" + path);
    return std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  };
  const std::string deck = text_of("inputs/identify_tir.lua"), doc = text_of("docs/mf_tire_files.md");
  // The number after the '/' of a "file / built" cell, or the first of a cell.
  const auto built = [](const std::string& cell) { return std::stod(cell.substr(cell.find('/') + 1)); };
  const std::regex entry(
      R"re(name = "([^"]+)"[\s\S]*?built = \{ width = ([0-9.]+), half_load = ([0-9.]+), translation = ([0-9.]+), rotation = ([0-9.]+) \})re");
  int rows = 0;
  for (auto match = std::sregex_iterator(deck.begin(), deck.end(), entry); match != std::sregex_iterator(); ++match) {
    const std::string name = (*match)[1];
    INFO(name);
    const size_t row = doc.find("\n| " + name + " ");
    REQUIRE(row != std::string::npos);
    std::vector<std::string> cells;
    std::istringstream line(doc.substr(row + 1, doc.find('\n', row + 1) - row - 1));
    for (std::string cell; std::getline(line, cell, '|');) cells.push_back(cell);
    REQUIRE(cells.size() >= 9);  // "", file, p, FNOMIN, w, K, F(d/2), f1, f0, ...
    CHECK(std::stod(cells[4]) == std::stod((*match)[2]));
    CHECK(built(cells[6]) == std::stod((*match)[3]));
    CHECK(built(cells[7]) == std::stod((*match)[4]));
    CHECK(built(cells[8]) == std::stod((*match)[5]));
    ++rows;
  }
  CHECK(rows == 5);
}

TEST_CASE("docs/mf_tire_files.md lists the sections tirefe reads in standard files and the keys it does not use",
          "[docs][tire_file][mf]") {
  std::ifstream in(std::string(TIREFE_SOURCE_DIR) + "/docs/mf_tire_files.md");
  const std::string doc{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string table = doc.substr(doc.find("| section | used | present in standard files, not used |"));
  for (const auto& [section, keys] : MfTireFile::unused_keys()) {
    CHECK_THAT(table, Contains("`[" + section + "]`"));
    for (const std::string& key : keys) {
      INFO(section << " " << key);
      CHECK_THAT(table, Contains("`" + key + "`"));
    }
  }
}
