// TeimOrbit property files (src/formats/teim_orbit.hpp), the format of tire (.tir) and road
// (.rdf) data: the parser, its syntax errors, the [UNITS] conversions, the schema reader's
// errors and the numbers the writer writes.
#include <catch2/catch.hpp>

#include <cmath>

#include "formats/teim_orbit.hpp"
#include "test_support.hpp"

using namespace tirefe;
using Catch::Matchers::Contains;
using tirefe::testing::replaced;
using tirefe::testing::same_bits;

namespace {

constexpr double kPi = 3.14159265358979323846;

const std::string kSiHeader =
    "[MDI_HEADER]\nFILE_TYPE = 'tir'\nFILE_VERSION = 1.0\nFILE_FORMAT = 'ASCII'\n"
    "[UNITS]\nLENGTH = 'meter'\nFORCE = 'newton'\nANGLE = 'radians'\nMASS = 'kg'\nTIME = 'second'\n";

}  // namespace

TEST_CASE("TeimOrbit files: sections, keys, strings, comments and tables, names in any case", "[io][teim_orbit]") {
  const std::string text =
      "$ a comment line\n"
      "! another one\n"
      "[MDI_HEADER]\n"
      "FILE_TYPE = 'rdf'\n"
      "(COMMENTS)\n"
      "{comment_string}\n"
      "'a $ in a string is no comment'\n"
      "[Parameters]\n"
      "  Height  =  10.5    $ mm\n"
      "name = \"with = and $\"\n"
      "bare = ASCII\n"
      "(XZ_DATA)\n"
      "{ x  z_l  z_r }\n"
      "0 1 2\n"
      "3, 4.5, -6e-1   $ commas too\n";
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(text, "road.rdf");
  REQUIRE(file.sections().size() == 2);
  const formats::TeimOrbitSection* parameters = file.section("PARAMETERS");
  REQUIRE(parameters != nullptr);
  CHECK(parameters->name == "Parameters");
  CHECK(parameters->line == 8);
  REQUIRE(parameters->values.size() == 3);
  CHECK(parameters->values[0].key == "Height");
  CHECK(parameters->values[0].text == "10.5");
  CHECK_FALSE(parameters->values[0].quoted);
  CHECK(parameters->values[1].text == "with = and $");
  CHECK(parameters->values[1].quoted);
  CHECK(parameters->values[2].text == "ASCII");
  REQUIRE(parameters->tables.size() == 1);
  const formats::TeimOrbitTable& table = parameters->tables[0];
  CHECK(table.columns == std::vector<std::string>{"x", "z_l", "z_r"});
  REQUIRE(table.rows.size() == 2);
  CHECK(table.rows[1] == std::vector<std::string>{"3", "4.5", "-6e-1"});
  CHECK(table.row_lines == std::vector<int>{14, 15});
  const formats::TeimOrbitTable& comments = file.section("mdi_header")->tables.at(0);
  CHECK(comments.rows.at(0) == std::vector<std::string>{"a $ in a string is no comment"});
}

TEST_CASE("TeimOrbit syntax errors name the file and line", "[io][teim_orbit]") {
  const std::pair<std::string, std::string> cases[] = {
      {"[A]\nK = 1\n[a]\n", "f.tir:3: section [a] appears twice (first at line 1)"},
      {"K = 1\n", "f.tir:1: 'K = 1' outside a section"},
      {"[A]\nK = 'abc\n", "f.tir:2: [A] K: unterminated string 'abc"},
      {"[A]\nK = 1 2\n", "f.tir:2: [A] K = 1 2: one value expected"},
      {"[A]\nwhat is this\n", "f.tir:2: expected [SECTION], (TABLE), KEY = value or a table row"},
      {"[A]\nK = 1\n2 3\n", "f.tir:3: expected [SECTION], (TABLE), KEY = value or a table row"},
      {"[A]\n1 2\nthree 4\n", "f.tir:3: [A] row 'three 4': the rows of a section's table are numbers"},
      {"[A\n", "f.tir:1: expected a section header [NAME]"},
      {"[A]\nK = 1\n{ x }\n", "f.tir:3: column names { ... } belong on the line after a table's (NAME)"},
      {"[A]\n(T)\n1 2\n(t)\n", "f.tir:4: [A] has two tables (t) (first at line 2)"},
      {"(T)\n", "f.tir:1: table (T) outside a section"},
      {std::string("[A]\nK = 208") + '\0' + "0\n", "f.tir:2: a NUL byte in the line: the file is damaged or not text"},
      {"[A]\nK = 'a\x01'\n", "f.tir:2: a control byte (0x01) in the line"},
  };
  for (const auto& [text, message] : cases) {
    INFO(text);
    CHECK_THROWS_WITH(formats::TeimOrbitFile::parse(text, "f.tir"), Contains(message));
  }
  CHECK_THROWS_WITH(formats::TeimOrbitFile::read("/nonexistent/x.tir"), Contains("x.tir: cannot open the file"));
}

TEST_CASE("[UNITS] converts every dimension to SI: mm, inch, lbf, lbm, degrees, milliseconds, kPa",
          "[io][teim_orbit]") {
  SECTION("mm and newton: one rounding, so a value in mm reads as the same double as in m") {
    const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(
        replaced(kSiHeader, "'meter'", "'MM'") + "[P]\nR = 271.5\nS = 1\nP = 0.25\n", "mm.tir");
    formats::TeimOrbitReader reader(file, "tir");
    CHECK(same_bits(*reader.number("P", "R", {1}), 0.2715));
    CHECK(*reader.number("p", "s", {-2, 1}) == 1e6);                // N/mm^2 = 1e6 N/m^2
    CHECK(*reader.number("P", "P", {0, 0, 0, 0, 0, 1}) == 0.25e6);  // pressure without PRESSURE: FORCE/LENGTH^2
    reader.finish();
  }
  SECTION("inch, lbf, lbm, degrees, milliseconds and a PRESSURE unit") {
    std::string header = kSiHeader;
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"'meter'", "'inch'"},
                                   {"'newton'", "'lbf'"},
                                   {"'radians'", "'degrees'"},
                                   {"'kg'", "'pound_mass'"},
                                   {"'second'", "'millisecond'"}})
      header = replaced(header, from, to);
    const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(
        header + "PRESSURE = 'kPa'\n[P]\nA = 10\nB = 2\nC = 90\nD = 1\nE = 5\nF = 1\nG = 208\nH = 3\nK = 1\n",
        "us.tir");
    formats::TeimOrbitReader reader(file, "tir");
    CHECK(*reader.number("P", "A", {1}) == Approx(0.254).epsilon(1e-15));
    CHECK(*reader.number("P", "B", {0, 1}) == Approx(8.896443230521).epsilon(1e-15));
    CHECK(*reader.number("P", "C", {0, 0, 0, 0, 1}) == Approx(kPi / 2).epsilon(1e-15));
    CHECK(*reader.number("P", "D", {0, 0, 1}) == Approx(0.45359237).epsilon(1e-15));
    CHECK(*reader.number("P", "E", {0, 0, 0, 1}) == Approx(0.005).epsilon(1e-15));
    CHECK(*reader.number("P", "F", {-2, 1}) == Approx(6894.757293168361).epsilon(1e-14));  // psi
    CHECK(*reader.number("P", "G", {0, 0, 0, 0, 0, 1}) == 208000.0);                       // kPa, not psi
    CHECK(*reader.number("P", "H", {2, 0, 1}) == Approx(3 * 0.45359237 * 0.0254 * 0.0254).epsilon(1e-14));
    CHECK(*reader.number("P", "K", {-1, 1, 0, 0, -1}) ==
          Approx(4.4482216152605 / 0.0254 / (kPi / 180)).epsilon(1e-14));  // lbf/(in deg)
    CHECK_FALSE(reader.number("P", "absent", {1}));
    reader.finish();
  }
  SECTION("the SI unit and the words of a dimension") {
    CHECK(formats::si_unit({-2, 1, 0, 1}) == "N s/m^2");
    CHECK(formats::si_unit({-1, 1, 0, 0, -1}) == "N/(m rad)");
    CHECK(formats::si_unit({2, 0, 1}) == "kg m^2");
    CHECK(formats::si_unit({-1, 0, 1}) == "kg/m");
    CHECK(formats::si_unit({}).empty());
    CHECK(formats::dimension_name({-2, 1, 0, 1}) == "force time/length^2");
    CHECK(formats::dimension_name({}) == "-");
  }
}

TEST_CASE("missing, unknown or misspelt units and headers are errors naming the file, line and quantity",
          "[io][teim_orbit]") {
  const std::pair<std::string, std::string> cases[] = {
      {replaced(kSiHeader, "'meter'", "'milimeter'"),
       "u.tir:6: [UNITS] LENGTH = 'milimeter' is not a known length unit (did you mean 'millimeter'?"},
      {replaced(kSiHeader, "'newton'", "'furlong'"), "u.tir:7: [UNITS] FORCE = 'furlong' is not a known force unit"},
      {replaced(kSiHeader, "MASS = 'kg'\n", ""), "u.tir:5: [UNITS] has no MASS (e.g. MASS = 'kg')"},
      {replaced(kSiHeader, "[UNITS]", "[UNIT]"), "u.tir: no [UNITS] section"},
      {replaced(kSiHeader, "FILE_TYPE = 'tir'", "FILE_TYPE = 'rdf'"),
       "u.tir:2: FILE_TYPE = 'rdf': this reader takes 'tir' files"},
      {replaced(kSiHeader, "FILE_FORMAT = 'ASCII'", "FILE_FORMAT = 'BINARY'"),
       "u.tir:4: [MDI_HEADER] FILE_FORMAT = 'BINARY': tirefe reads text files"},
      {replaced(kSiHeader, "FILE_VERSION = 1.0", "FILE_VERSION = one"),
       "u.tir:3: [MDI_HEADER] FILE_VERSION = one is not a finite number"},
      {kSiHeader + "MASS = 'gram'\n", "u.tir:11: [UNITS] MASS is given twice (first at line 9)"},
      {kSiHeader + "PRESSURE = 'atm'\n", "u.tir:11: [UNITS] PRESSURE = 'atm' is not a known pressure unit"},
  };
  for (const auto& [text, message] : cases) {
    INFO(text);
    const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(text, "u.tir");
    CHECK_THROWS_WITH(formats::TeimOrbitReader(file, "tir"), Contains(message));
  }
  SECTION("a value that is not a number, and keys and sections nobody asked for") {
    const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(
        kSiHeader + "[TREAD]\nWIDTH = wide\nDEPTH = '1'\nWIDHT = 2\n[TRED]\nX = 1\n", "v.tir");
    formats::TeimOrbitReader reader(file, "tir");
    CHECK_THROWS_WITH(reader.number("TREAD", "WIDTH", {1}), Contains("v.tir:12: [TREAD] WIDTH = wide is not a finite"));
    CHECK_THROWS_WITH(reader.number("TREAD", "DEPTH", {1}), Contains("v.tir:13: [TREAD] DEPTH = '1' is a string"));
    reader.number("TREAD", "LENGTH", {1});
    CHECK_THROWS_WITH(reader.finish(), Contains("v.tir:14: [TREAD] unknown key 'WIDHT' (did you mean 'WIDTH'?; "
                                                "known keys: DEPTH, LENGTH, WIDTH)"));
    const formats::TeimOrbitFile other =
        formats::TeimOrbitFile::parse(kSiHeader + "[TREAD]\nWIDTH = 1\n[TRED]\nX = 1\n", "w.tir");
    formats::TeimOrbitReader second(other, "tir");
    second.number("TREAD", "WIDTH", {1});
    CHECK_THROWS_WITH(second.finish(), Contains("w.tir:13: unknown section [TRED] (did you mean '[TREAD]'?"));
  }
}

TEST_CASE("numbers are written in the shortest text that reads back bit for bit", "[io][teim_orbit]") {
  CHECK(formats::round_trip_number(0.543) == "0.543");
  CHECK(formats::round_trip_number(100) == "100");
  CHECK(formats::round_trip_number(0.1 + 0.2) == "0.30000000000000004");
  CHECK(formats::round_trip_number(-0.0) == "-0");
  CHECK(formats::round_trip_number(2.4e3) == "2400");
  for (double value : {1.0 / 3.0, 5e-324, 1.7976931348623157e308, -2.2250738585072014e-308, 0.2715 * 2}) {
    INFO(value);
    CHECK(same_bits(std::strtod(formats::round_trip_number(value).c_str(), nullptr), value));
  }
}

TEST_CASE("TeimOrbit files as MF-Tyre writes them: no header, blank values, a section's own table",
          "[io][teim_orbit]") {
  // The layouts of public Magic Formula files: [SHAPE] holds its rows right after its header,
  // with or without a column line; a parameter left blank ('KEY =') is absent; [MDI_HEADER]
  // may be missing.
  const std::string units = kSiHeader.substr(kSiHeader.find("[UNITS]"));
  const std::string text = units +
                           "[MODEL]\nFITTYP = 61\nROAD_INCREMENT =\nROAD_DIRECTION =   $ blank\n"
                           "[SHAPE]\n{radial width}\n 1.0 0.0\n 1.0 0.4\n 0.9 1.0\n"
                           "[DEFLECTION_LOAD_CURVE]\n 0.000 0.0\n 0.005 2004.057\n"
                           "[VERTICAL]\nFNOMIN = 4000\nVERTICAL_STIFFNESS =\n";
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(text, "mf.tir");
  const formats::TeimOrbitTable* shape = file.section("shape")->own_table();
  REQUIRE(shape != nullptr);
  CHECK(shape->columns == std::vector<std::string>{"radial", "width"});
  CHECK(shape->rows.size() == 3);
  CHECK(shape->row_lines.front() == 13);
  const formats::TeimOrbitTable* curve = file.section("DEFLECTION_LOAD_CURVE")->own_table();
  REQUIRE(curve != nullptr);
  CHECK(curve->columns.empty());
  CHECK(curve->rows.at(1) == std::vector<std::string>{"0.005", "2004.057"});

  formats::TeimOrbitReader reader(file, "tir");
  CHECK_FALSE(reader.number("MODEL", "ROAD_INCREMENT"));
  CHECK(*reader.number("VERTICAL", "FNOMIN", {0, 1}) == 4000.0);
  CHECK_FALSE(reader.number("VERTICAL", "VERTICAL_STIFFNESS", {-1, 1}));
  CHECK_THROWS_WITH(reader.required_number("VERTICAL", "VERTICAL_STIFFNESS", {-1, 1}, "the stiffness"),
                    Contains("mf.tir:21: [VERTICAL] VERTICAL_STIFFNESS has no value (the stiffness"));
  CHECK(reader.row_numbers(*reader.table("SHAPE", ""), 2, {}) == std::vector<double>{0.9, 1.0});
}

TEST_CASE("a foreign file is read leniently: what tirefe does not read is passed over, a misspelt key it reads is not",
          "[io][teim_orbit]") {
  const std::string text = kSiHeader +
                           "[VERTICAL]\nFNOMIN = 4000\nQ_FZ1 = 1\nDYNAMIC_STIFFNESS = 0\n"
                           "[GOODYEAR]\nCONSTRUCTION = '0L5001'\nTEST_NUMBER = ''\nK = 1\nK = 2\n";
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::parse(text, "f.tir");
  formats::TeimOrbitReader reader(file, "tir");
  reader.number("VERTICAL", "FNOMIN", {0, 1});
  reader.number("VERTICAL", "Q_FZ2");
  // Q_FZ1 is a standard key tirefe lists as unused; DYNAMIC_STIFFNESS is like no key it reads;
  // [GOODYEAR] (and its repeated key) is a section tirefe does not read.
  reader.finish_foreign({{"VERTICAL", {"Q_FZ1"}}});
  CHECK_THROWS_WITH(reader.finish(), Contains("f.tir:13: [VERTICAL] unknown key 'Q_FZ1'"));
  CHECK_THROWS_WITH(reader.finish_foreign({{"VERTICAL", {}}}),
                    Contains("f.tir:13: [VERTICAL] unknown key 'Q_FZ1' (did you mean 'Q_FZ2'? tirefe reads that one"));
  CHECK_THROWS_WITH(reader.number("GOODYEAR", "K"),
                    Contains("f.tir:19: [GOODYEAR] K is given twice (first at line 18)"));
}
