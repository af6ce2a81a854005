// Road files (src/formats/road_file.hpp): CSV profiles with units, the 2D road types of
// road data files (.rdf) against hand-computed geometry, left and right tracks, the
// placement by the surface macro, and the errors.
#include <catch2/catch.hpp>

#include <cmath>

#include "deck_support.hpp"
#include "formats/road_file.hpp"
#include "formats/teim_orbit.hpp"
#include "test_support.hpp"
#include "tirefe/test_paths.hpp"

using namespace tirefe;
using Catch::Matchers::Contains;
using tirefe::testing::replaced;
using tirefe::testing::TempDir;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string rdf(const std::string& units, const std::string& model, const std::string& parameters) {
  return "[MDI_HEADER]\nFILE_TYPE = 'rdf'\nFILE_VERSION = 5.0\nFILE_FORMAT = 'ASCII'\n"
         "[UNITS]\nLENGTH = '" +
         units +
         "'\nFORCE = 'newton'\nANGLE = 'degrees'\nMASS = 'kg'\nTIME = 'second'\n"
         "[MODEL]\nMETHOD = '2D'\n" +
         model + "\n[PARAMETERS]\n" + parameters;
}

void check_points(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& expected,
                  double tolerance = 1e-15) {
  REQUIRE(points.size() == expected.size());
  for (size_t i = 0; i < points.size(); ++i) {
    INFO("point " << i << ": (" << points[i].x() << ", " << points[i].y() << ")");
    CHECK((points[i] - expected[i]).norm() <= tolerance);
  }
}

/// The profile is level at 'height' over x: a point 2 mm above projects straight down onto it.
void check_height(const RoadProfile& road, double x, double height) {
  INFO("x = " << x);
  const SurfaceProjection projection = road.project({x, height + 0.002}, 0.0);
  CHECK((projection.point - Eigen::Vector2d(x, height)).norm() < 1e-14);
  CHECK(projection.gap == Approx(0.002).margin(1e-14));
  CHECK((projection.normal - Eigen::Vector2d::UnitY()).norm() < 1e-14);
}

}  // namespace

TEST_CASE("CSV road profiles: units in the header, names of the columns, left and right tracks",
          "[contact][road_file]") {
  TempDir folder;
  const std::string tracks = folder.write("tracks.csv",
                                          "# a measured road\n"
                                          "distance [mm], height_left_mm, z_right [in]\n"
                                          "0, 0, 0\n"
                                          "100, 5, 1\n"
                                          "250, 5, 1\n"
                                          "400, 0, 1   # the right track stays up\n");
  check_points(read_road_csv(tracks, RoadTrack::Left), {{0, 0}, {0.1, 0.005}, {0.25, 0.005}, {0.4, 0}});
  check_points(read_road_csv(tracks, RoadTrack::Right), {{0, 0}, {0.1, 0.0254}, {0.25, 0.0254}, {0.4, 0.0254}});
  // One track serves both; a point that repeats the one before (a vertical step written twice) is skipped.
  const std::string single = folder.write("single.csv", "x_m,z_m\n-1,0\n0,0\n0,0\n0,0.02\n1,0.02\n");
  check_points(read_road_csv(single, std::nullopt), {{-1, 0}, {0, 0}, {0, 0.02}, {1, 0.02}});
  check_points(read_road_csv(single, RoadTrack::Right), {{-1, 0}, {0, 0}, {0, 0.02}, {1, 0.02}});
  // No unit: metres.
  check_points(read_road_csv(folder.write("bare.csv", "x,height\n0,1\n2,3\n"), std::nullopt), {{0, 1}, {2, 3}});

  const std::pair<std::string, std::string> errors[] = {
      {"x_mm,z_left_mm,z_right_mm\n0,0,0\n1,1,1\n", "holds a left and a right track: give track = \"left\""},
      {"x_m,speed_m/s\n0,0\n1,1\n", "column 'speed_m/s' is not part of a road profile"},
      {"x_m,z_N\n0,0\n1,1\n", "column 'z_N' is in N, not a length"},
      {"x_m,z_m\n0,0\n2,0\n# dip\n1,0\n", "bad.csv:5: x = 1 m comes after x = 2 m (x must not decrease)"},
      {"x [furlong],z [mm]\n0,0\n1,1\n", "bad.csv:1: column 'x [furlong]': write the unit as 'name [unit]'"},
      {"z_m\n0\n1\n", "no position column (x, s or distance"},
      {"x_m,z_m,z_left_m,z_right_m\n0,0,0,0\n1,1,1,1\n", "give one height column (z or height) or one per track"},
      {"x_m,z_m,height_m\n0,0,0\n1,1,1\n", "columns 'z_m' and 'height_m' say the same"},
      {"x_m,z_m\n0,0\n", "at least two distinct points"},
      {"Distance (furlong);Height (m)\n0;0\n1;1\n", "bad.csv:1: column 'Distance (furlong)': write the unit as"},
      {"x_m;z_m\n0;0\n1,5;0,1;2\n", "bad.csv:3: expected 2 values (x_m, z_m), found 3"},
      {"x_m,z_m\n0,0\n1;0\n", "bad.csv:3: expected 2 values (x_m, z_m), found 1"},
  };
  for (const auto& [text, message] : errors) {
    INFO(text);
    CHECK_THROWS_WITH(read_road_csv(folder.write("bad.csv", text), std::nullopt), Contains(message));
  }
}

TEST_CASE("road data files: a flat road at its OFFSET", "[contact][road_file]") {
  TempDir folder;
  const RoadShape shape = read_road_data_file(
      folder.write("flat.rdf", rdf("mm", "ROAD_TYPE = 'flat'", "OFFSET = 25\nMU = 1.0\n")), std::nullopt);
  CHECK(shape.kind == RoadShape::Kind::Flat);
  CHECK(shape.level == 0.025);
  CHECK(shape.road_type == "flat");
  // A flat road needs no [PARAMETERS].
  const std::string bare =
      "[MDI_HEADER]\nFILE_TYPE = 'rdf'\nFILE_VERSION = 5.0\nFILE_FORMAT = 'ASCII'\n"
      "[UNITS]\nLENGTH = 'meter'\nFORCE = 'newton'\nANGLE = 'radians'\nMASS = 'kg'\n"
      "TIME = 'second'\n[MODEL]\nMETHOD = '2D'\nROAD_TYPE = 'FLAT'\nFUNCTION_NAME = 'ARC904'\n";
  CHECK(read_road_data_file(folder.write("bare.rdf", bare), RoadTrack::Left).level == 0.0);
}

TEST_CASE("road data files: poly_line tracks in mm and in inches, two, three and four columns",
          "[contact][road_file]") {
  TempDir folder;
  const std::string three =
      folder.write("three.rdf", rdf("mm", "ROAD_TYPE = 'poly_line'",
                                    "OFFSET = 10\n(XZ_DATA)\n{ x z_l z_r }\n0 0 0\n900 0 0\n1000 100 -50\n1240 0 0\n"));
  check_points(read_road_data_file(three, RoadTrack::Left).points, {{0, 0.01}, {0.9, 0.01}, {1, 0.11}, {1.24, 0.01}});
  check_points(read_road_data_file(three, RoadTrack::Right).points, {{0, 0.01}, {0.9, 0.01}, {1, -0.04}, {1.24, 0.01}});
  // Four columns: each track has its own x (here the right one lags by 10 inches).
  const std::string four = folder.write(
      "four.rdf", rdf("inch", "ROAD_TYPE = 'poly_line'", "(XZ_DATA)\n{}\n0 0 10 0\n20 1 30 2\n40 1 50 2\n"));
  check_points(read_road_data_file(four, RoadTrack::Left).points, {{0, 0}, {0.508, 0.0254}, {1.016, 0.0254}}, 1e-15);
  check_points(read_road_data_file(four, RoadTrack::Right).points, {{0.254, 0}, {0.762, 0.0508}, {1.27, 0.0508}},
               1e-15);
  // Two columns serve both tracks.
  const std::string two = folder.write("two.rdf", rdf("meter", "ROAD_TYPE = 'poly_line'", "(XZ_DATA)\n0 0\n1 0.1\n"));
  check_points(read_road_data_file(two, std::nullopt).points, {{0, 0}, {1, 0.1}});
}

TEST_CASE("road data files: a plank's 45 degree bevels and a groove", "[contact][road_file]") {
  TempDir folder;
  const std::string plank = folder.write(
      "plank.rdf", rdf("mm", "ROAD_TYPE = 'plank'",
                       "OFFSET = 10\nHEIGHT = 20\nSTART = 1000\nLENGTH = 100\nBEVEL_EDGE_LENGTH = 5\nDIRECTION = 0\n"));
  const RoadShape shape = read_road_data_file(plank, std::nullopt);
  check_points(shape.points, {{1, 0.01}, {1, 0.025}, {1.005, 0.03}, {1.095, 0.03}, {1.1, 0.025}, {1.1, 0.01}});
  const RoadProfile road(shape.points);
  check_height(road, 0.5, 0.01);
  check_height(road, 1.05, 0.03);
  check_height(road, 1.5, 0.01);
  // Above the middle of the front bevel, along its normal: the bevel is at 45 degrees.
  const Eigen::Vector2d normal = Eigen::Vector2d(-1.0, 1.0).normalized();
  const SurfaceProjection front = road.project(Eigen::Vector2d(1.0025, 0.0275) + 0.002 * normal, 0.0);
  CHECK(front.gap == Approx(0.002).margin(1e-14));
  CHECK((front.normal - normal).norm() < 1e-12);
  // A bevel as long as the plank is high leaves no vertical face; a negative height is a groove.
  check_points(read_road_data_file(folder.write("full.rdf", rdf("mm", "ROAD_TYPE = 'plank'",
                                                                "HEIGHT = 5\nSTART = 0\nLENGTH = 20\n"
                                                                "BEVEL_EDGE_LENGTH = 5\n")),
                                   std::nullopt)
                   .points,
               {{0, 0}, {0.005, 0.005}, {0.015, 0.005}, {0.02, 0}});
  check_points(read_road_data_file(folder.write("groove.rdf", rdf("mm", "ROAD_TYPE = 'plank'",
                                                                  "HEIGHT = -20\nSTART = 0\nLENGTH = 100\n"
                                                                  "BEVEL_EDGE_LENGTH = 5\n")),
                                   std::nullopt)
                   .points,
               {{0, 0}, {0, -0.015}, {0.005, -0.02}, {0.095, -0.02}, {0.1, -0.015}, {0.1, 0}});
}

TEST_CASE("road data files: a pot hole's edges and depth, and a bump from a negative depth", "[contact][road_file]") {
  TempDir folder;
  const std::string hole = folder.write(
      "hole.rdf", rdf("mm", "ROAD_TYPE = 'pot_hole'", "DEPTH = 50\nSTART = 2000\nLENGTH = 300\nDIRECTION = 0.0\n"));
  const RoadShape shape = read_road_data_file(hole, RoadTrack::Right);
  check_points(shape.points, {{2, 0}, {2, -0.05}, {2.3, -0.05}, {2.3, 0}});
  const RoadProfile road(shape.points);
  check_height(road, 1.9, 0.0);
  check_height(road, 2.15, -0.05);
  check_height(road, 2.4, 0.0);
  // The edges: just before the hole the road is there; over the hole's middle at road level
  // the bottom is 50 mm away; a point beside the far wall is nearer the wall than the bottom.
  CHECK(road.project({1.99, 0.02}, 0.0).gap == Approx(0.02).margin(1e-14));
  CHECK(road.project({2.15, 0.0}, 0.0).gap == Approx(0.05).margin(1e-14));
  const SurfaceProjection wall = road.project({2.29, -0.03}, 0.0);
  CHECK(wall.gap == Approx(0.01).margin(1e-14));
  CHECK(wall.point.x() == Approx(2.3).margin(1e-14));
  const RoadShape bump = read_road_data_file(
      folder.write("bump.rdf", rdf("mm", "ROAD_TYPE = 'pot_hole'", "DEPTH = -30\nSTART = 0\nLENGTH = 100\n")),
      std::nullopt);
  check_points(bump.points, {{0, 0}, {0, 0.03}, {0.1, 0.03}, {0.1, 0}});
}

TEST_CASE("road data files: a drum of DIAMETER with a rounded cleat", "[contact][road_file]") {
  TempDir folder;
  const std::string drum =
      folder.write("drum.rdf", rdf("mm", "ROAD_TYPE = 'drum'",
                                   "DIAMETER = 1700\nNUMBER_CLEATS = 1\nCLEAT_HEIGHT = 25\nCLEAT_LENGTH = 20\n"
                                   "CLEAT_STARTING_ANGLE = 10\nCLEAT_BEVEL_EDGE_LENGTH = 5\nCLEAT_EDGE_ROUNDED = 1\n"));
  const RoadShape shape = read_road_data_file(drum, std::nullopt);
  CHECK(shape.kind == RoadShape::Kind::Drum);
  CHECK(shape.diameter == 1.7);
  CHECK(shape.cleat.height == 0.025);
  CHECK(shape.cleat.arc_length == 0.02);
  CHECK(shape.cleat.angle == Approx(kPi / 2 + 10 * kPi / 180).epsilon(1e-15));
  CHECK(shape.cleat.edge_radius == 0.005);
  const Drum surface(shape.diameter, Eigen::Vector2d::Zero(), MotionFunction(), shape.cleat);
  const Eigen::Vector2d radial(std::cos(shape.cleat.angle), std::sin(shape.cleat.angle));
  CHECK(surface.project(1.0 * radial, 0.0).gap == Approx(1.0 - 0.875).margin(1e-12));  // on the cleat's top
  const Eigen::Vector2d top(0.0, 1.0);  // 10 degrees from the cleat: the bare drum
  CHECK(surface.project(1.0 * top, 0.0).gap == Approx(1.0 - 0.85).margin(1e-12));
  const RoadShape bare = read_road_data_file(
      folder.write("bare.rdf", rdf("meter", "ROAD_TYPE = 'drum'", "DIAMETER = 2.5\n")), std::nullopt);
  CHECK(bare.diameter == 2.5);
  CHECK(bare.cleat.height == 0.0);
}

TEST_CASE("road data file errors name the file, the line and the key", "[contact][road_file]") {
  TempDir folder;
  const std::string plank = "HEIGHT = 20\nSTART = 0\nLENGTH = 100\n";
  struct Case {
    std::string text, message;
  };
  const Case cases[] = {
      {rdf("mm", "ROAD_TYPE = 'plank'", "HIEGHT = 20\nSTART = 0\nLENGTH = 100\n"),
       "bad.rdf:15: [PARAMETERS] unknown key 'HIEGHT' (did you mean 'HEIGHT'?"},
      {rdf("mm", "ROAD_TYPE = 'plank'", "START = 0\nLENGTH = 100\n"), "bad.rdf:14: missing [PARAMETERS] HEIGHT"},
      {rdf("mm", "ROAD_TYPE = 'sine'", "AMPLITUDE = 5\n"),
       "bad.rdf:13: [MODEL] ROAD_TYPE = 'sine': tirefe reads the 2D road types flat, poly_line, plank, pot_hole"},
      {testing::replaced(rdf("mm", "ROAD_TYPE = 'flat'", ""), "METHOD = '2D'", "METHOD = '3D'"),
       "bad.rdf:12: [MODEL] needs METHOD = '2D'"},
      {rdf("mm", "ROAD_TYPE = 'poly_line'", "(XZ_DATA)\n0 0 0\n1 1 1\n"),
       "bad.rdf:15: (XZ_DATA) holds a left and a right track: give track"},
      {rdf("mm", "ROAD_TYPE = 'poly_line'", "(XZ_DATA)\n0 0\n2 0\n1 0\n"),
       "bad.rdf:18: (XZ_DATA), left track: x = 0.001 m comes after x = 0.002 m (x must not decrease)"},
      {rdf("mm", "ROAD_TYPE = 'poly_line'", "(XZ_DATA)\n0 0\n2 zero\n"), "bad.rdf:17: (XZ_DATA) row: 'zero' is not"},
      {rdf("mm", "ROAD_TYPE = 'poly_line'", "(XZ_DATA)\n0 0\n2 0 3\n"), "bad.rdf:17: (XZ_DATA) row has 3 values"},
      {rdf("mm", "ROAD_TYPE = 'poly_line'", "OFFSET = 1\n"), "a poly_line road needs its profile as an (XZ_DATA)"},
      {rdf("mm", "ROAD_TYPE = 'plank'", plank + "DIRECTION = 30\n"), "bad.rdf:18: [PARAMETERS] DIRECTION must be 0"},
      {rdf("mm", "ROAD_TYPE = 'plank'", plank + "BEVEL_EDGE_LENGTH = 30\n"),
       "bad.rdf:18: [PARAMETERS] BEVEL_EDGE_LENGTH must be between 0 and the plank's height"},
      {rdf("mm", "ROAD_TYPE = 'pot_hole'", "DEPTH = 0\nSTART = 0\nLENGTH = 100\n"),
       "bad.rdf:15: [PARAMETERS] DEPTH must not be 0"},
      {rdf("mm", "ROAD_TYPE = 'flat'", "MU = 0.8\n"), "bad.rdf:15: [PARAMETERS] MU must be 1"},
      {rdf("mm", "ROAD_TYPE = 'flat'", "ROTATION_ANGLE_XY_PLANE = 180\n"),
       "bad.rdf:15: [PARAMETERS] ROTATION_ANGLE_XY_PLANE must be 0"},
      {rdf("mm", "ROAD_TYPE = 'drum'",
           "DIAMETER = 1700\nNUMBER_CLEATS = 1\nCLEAT_HEIGHT = 25\nCLEAT_LENGTH = 20\nCLEAT_STARTING_ANGLE = 0\n"
           "CLEAT_BEVEL_EDGE_LENGTH = 5\n"),
       "bad.rdf:20: [PARAMETERS] CLEAT_BEVEL_EDGE_LENGTH > 0 with flat bevels is not modelled"},
      {rdf("mm", "ROAD_TYPE = 'drum'", "DIAMETER = 1700\nNUMBER_CLEATS = 2\n"),
       "bad.rdf:16: [PARAMETERS] NUMBER_CLEATS must be 0 or 1"},
      {rdf("mm", "ROAD_TYPE = 'drum'", "DIAMETER = 1700\nNUMBER_CLEATS = 1\nCLEAT_HEIGHT = 25\n"),
       "a cleat needs CLEAT_HEIGHT, CLEAT_LENGTH"},
      {rdf("mm", "ROAD_TYPE = 'drum'", "DIAMETER = 1700\nOFFSET = 5\n"), "bad.rdf:16: [PARAMETERS] OFFSET must be 0"},
      {rdf("mm", "ROAD_TYPE = 'flat'\nROAD_TYPE = 'drum'", ""), "bad.rdf:14: [MODEL] ROAD_TYPE is given twice"},
      {rdf("mm", "ROAD_TYPE = 'flat'", "") + "[GRAPHICS]\nX = 1\n", "bad.rdf:15: unknown section [GRAPHICS]"},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    CHECK_THROWS_WITH(read_road_data_file(folder.write("bad.rdf", c.text), std::nullopt), Contains(c.message));
  }
}

TEST_CASE("the surface macro places road files: type from the .rdf, start, offset, track", "[contact][road_file]") {
  TempDir folder;
  folder.write("plank.rdf", rdf("mm", "ROAD_TYPE = 'plank'", "HEIGHT = 20\nSTART = 100\nLENGTH = 100\n"));
  folder.write("drum.rdf", rdf("mm", "ROAD_TYPE = 'drum'",
                               "DIAMETER = 2000\nNUMBER_CLEATS = 1\nCLEAT_HEIGHT = 25\nCLEAT_LENGTH = 50\n"
                               "CLEAT_STARTING_ANGLE = 90\n"));
  folder.write("road.csv", "x_mm,z_left_mm,z_right_mm\n0,0,0\n100,10,-10\n");
  folder.write("road.txt", "0 0\n1 0.5\n");
  const std::string deck = folder.write("roads.lua", R"(
local model = tirefe.model{}
model:surface{ name = "plank", file = "plank.rdf", start = 2.0, offset = -0.3 }
model:surface{ name = "drum", file = "drum.rdf", centre = { 0, -1 } }
model:surface{ name = "right", type = "profile", file = "road.csv", track = "right", start = -1.0 }
model:surface{ name = "text", type = "profile", file = "road.txt", offset = 1.0 }
local function gap(surface, x, y) return model:surface_projection{ surface = surface, point = { x, y } }.gap end
-- The plank's 0.1 m start lands at 2.1 m, 20 mm above the road at -0.3 m.
tirefe.check{ name = "plank top", value = gap("plank", 2.15, 0), expected = 0.3 - 0.02, tolerance = 1e-14 }
tirefe.check{ name = "road before the plank", value = gap("plank", 1.5, 0), expected = 0.3, tolerance = 1e-14 }
tirefe.check{ name = "road after the plank", value = gap("plank", 2.8, 0), expected = 0.3, tolerance = 1e-14 }
-- The drum's top at (0, 0); the cleat 90 degrees counter-clockwise from it, on the -x side.
tirefe.check{ name = "drum top", value = gap("drum", 0, 0.1), expected = 0.1, tolerance = 1e-12 }
tirefe.check{ name = "cleat", value = gap("drum", -1.5, -1), expected = 0.5 - 0.025, tolerance = 1e-12 }
-- The right track descends 10 mm over its 0.1 m, from x = -1.
tirefe.check{ name = "right track", value = gap("right", 0.5, 0.1), expected = 0.11, tolerance = 1e-14 }
tirefe.check{ name = "text profile raised", value = gap("text", 2, 2), expected = 0.5, tolerance = 1e-14 }
local p = model:surface_projection{ surface = "plank", point = { 2.15, 1 }, time = 0 }
tirefe.check{ name = "closest point", value = p.y, expected = -0.28, tolerance = 1e-14 }
tirefe.check{ name = "normal", value = p.normal[2], expected = 1, tolerance = 1e-14 }
)");
  testing::check_deck_passes(deck, folder.path("out"), 9);

  const std::pair<std::string, std::string> errors[] = {
      {"model:surface{ name = \"s\", type = \"drum\", file = \"plank.rdf\" }",
       "type 'drum', but '" + folder.path("plank.rdf") + "' holds a plank road (type 'profile')"},
      {"model:surface{ name = \"s\", file = \"road.txt\" }", "give 'type' (flat, drum or profile)"},
      {"model:surface{ name = \"s\", type = \"profile\", points = {{0, 0}, {1, 0}}, start = 1 }",
       "'start' places a road read from a 'file'"},
      {"model:surface{ name = \"s\", type = \"profile\", file = \"road.txt\", track = \"left\" }",
       "'track' picks the track of a file with two (.csv, .rdf); '" + folder.path("road.txt") + "' has one"},
      {"model:surface{ name = \"s\", type = \"profile\", file = \"road.csv\" }", "give track = \"left\" or \"right\""},
      {"model:surface{ name = \"s\", file = \"drum.rdf\", diameter = 2 }", "'diameter' is given by the file"},
      {"model:surface{ name = \"s\", file = \"drum.rdf\", offset = 1 }", "'offset' does not apply to a drum surface"},
      {"model:surface{ name = \"s\", type = \"flat\", edge_radius = 0.01 }",
       "'edge_radius' does not apply to a flat surface"},
      {"model:surface{ name = \"s\", type = \"flat\", file = \"road.txt\" }",
       "'file' does not apply to a flat surface"},
      {"model:surface{ name = \"s\", type = \"drum\", diameter = 2, level = 1 }",
       "'level' does not apply to a drum surface"},
      {"model:surface{ name = \"s\", type = \"drum\", diameter = 2, file = \"road.txt\" }",
       "'file' does not apply to a drum surface"},
      {"model:surface{ name = \"s\", type = \"profile\", points = {{0, 0}, {1, 0}}, centre = { 0, 0 } }",
       "'centre' does not apply to a profile surface"},
      {"model:surface{ name = \"s\", type = \"profile\", file = \"road.txt\", level = 1 }",
       "'level' is the road around a 'pothole' or 'cleat'"},
      {"model:surface{ name = \"s\", file = \"plank.rdf\", track = \"middle\" }", "must be one of left, right"},
      {"model:surface{ name = \"s\", file = \"none.rdf\" }", "none.rdf: cannot open the file"},
  };
  for (const auto& [body, message] : errors) {
    const auto bad = testing::run_deck_in_process(
        folder.write("bad.lua", "local model = tirefe.model{}\n" + body + "\n"), folder.path("out"));
    CHECK_THAT(bad.error, Contains("bad.lua:2: ") && Contains(message));
  }
}

TEST_CASE("inputs/road_files.lua: the chuckhole read from .rdf and .csv equals the built-in one",
          "[contact][road_file][decks]") {
  TempDir folder;
  testing::check_deck_passes(std::string(TIREFE_SOURCE_DIR) + "/inputs/road_files.lua", folder.path("out"), 5);
}

TEST_CASE("CSV road profiles as spreadsheets write them: semicolons or tabs, decimal commas, 'Distance (m)'",
          "[contact][road_file]") {
  TempDir folder;
  // A European spreadsheet: semicolons between the fields, commas in the numbers.
  const std::string semicolons = folder.write("semicolons.csv",
                                              "Distance (m);Elevation (mm)\n"
                                              "0;0\n"
                                              "1,5;12,5\n"
                                              "3;-2,25\n");
  check_points(read_road_csv(semicolons, std::nullopt), {{0, 0}, {1.5, 0.0125}, {3, -0.00225}}, 1e-17);
  const std::string tabs =
      folder.write("tabs.csv", "S [m]\tZ_Left [mm]\tZ_Right [mm]\n0\t0\t0\n2.5\t10\t-10\n5\t0\t0\n");
  check_points(read_road_csv(tabs, RoadTrack::Right), {{0, 0}, {2.5, -0.01}, {5, 0}});
  // A decimal comma with commas between the fields is a field too many, with the line.
  CHECK_THROWS_WITH(read_road_csv(folder.write("mixed.csv", "x_m,z_m\n0,0\n1,5,0\n"), std::nullopt),
                    Contains("mixed.csv:3: expected 2 values (x_m, z_m), found 3"));
}

TEST_CASE("road data files as real ones come: no [MDI_HEADER], 'sec' and 'degree', column names as a comment",
          "[contact][road_file]") {
  TempDir folder;
  const std::string path = folder.write("plateau.rdf",
                                        "!\n! road data file\n!\n"
                                        "$---------------------------------------------------------------UNITS\n"
                                        "[UNITS]\nLENGTH = 'meter'\nFORCE = 'newton'\nANGLE = 'degree'\nMASS = 'kg'\n"
                                        "TIME = 'sec'\n"
                                        "[MODEL]\nMETHOD = '2D'\nROAD_TYPE = 'poly_line'\n"
                                        "[PARAMETERS]\nMU = 1.0   $ peak friction scaling\nOFFSET = 0\n"
                                        "ROTATION_ANGLE_XY_PLANE = 0\n$\n$   X_road   Z_left   Z_right\n(XZ_DATA)\n"
                                        "   -100.000   0.000   0.000\n   0.000   0.000   0.000\n"
                                        "   3.500   0.036   0.030\r\n   7.000   0.137   0.120\n");
  check_points(read_road_data_file(path, RoadTrack::Left).points, {{-100, 0}, {0, 0}, {3.5, 0.036}, {7, 0.137}});
  check_points(read_road_data_file(path, RoadTrack::Right).points, {{-100, 0}, {0, 0}, {3.5, 0.030}, {7, 0.120}});
  CHECK_THROWS_WITH(read_road_data_file(path, std::nullopt),
                    Contains("plateau.rdf:20: (XZ_DATA) holds a left and a right track: give track"));
}

namespace {

// An LRFI file: the heading, the reference line's slope and banking, three long sections
// 0.5 m apart centred on the reference line, a row of 10 cm steps along u.
std::string opencrg(const std::string& road_keys, const std::string& extra_sections, const std::string& data) {
  return "$CT\na test road\n$\n$ROAD_CRG\n" + road_keys + "$\n" + extra_sections +
         "$KD_DEFINITION\n#:LRFI\nD:reference line phi,rad\nD:reference line slope,m/m\n"
         "D:reference line banking,m/m\nD:long section 1,m\nD:long section 2,m\nD:long section 3,m\n$\n"
         "$$$$$$$$$$\n" +
         data;
}

const std::string kCrgKeys = "REFERENCE_LINE_INCREMENT = 0.1\nLONG_SECTION_V_INCREMENT = 0.5   ! centred\n";
//                          phi       slope     banking   v = -0.5  v = 0     v = 0.5
const std::string kCrgData =
    " *missing* *missing* 0.0000000 0.0000000 0.0010000 0.0020000\n"
    " 0.0000000 0.0100000 0.0200000-0.0010000 0.0030000 0.0050000\n"
    " 0.0000000-0.0200000 0.0000000 *missing* 0.0040000 0.0060000\n";

}  // namespace

TEST_CASE("OpenCRG files: a track along the reference line from the long sections, slope and banking",
          "[contact][road_file][opencrg]") {
  TempDir folder;
  const std::string path =
      folder.write("road.crg", opencrg(kCrgKeys, "$ROAD_CRG_OPTS\nBORDER_MODE_U = 2\n$\n", kCrgData));
  // v = 0: the middle section, raised by the reference line's height from its slope (the
  // first row's slope leads nowhere): 0, +0.01 * 0.1, then -0.02 * 0.1.
  check_points(read_opencrg(path, 0.0), {{0, 0.001}, {0.1, 0.001 + 0.003}, {0.2, -0.001 + 0.004}}, 1e-15);
  // v = 0.25: halfway to the left section, plus the banking times v.
  check_points(read_opencrg(path, 0.25), {{0, 0.0015}, {0.1, 0.001 + 0.004 + 0.02 * 0.25}, {0.2, -0.001 + 0.005}},
               1e-15);
  // A track through a missing value is refused with its line; one outside the road too.
  CHECK_THROWS_WITH(read_opencrg(path, -0.5),
                    Contains("road.crg:23: no height at u = 0.2 m (a missing value): the track at v = -0.5 m"));
  CHECK_THROWS_WITH(read_opencrg(path, 0.6),
                    Contains("v = 0.6 m lies outside the road's long sections (v from -0.5 to 0.5 m)"));
  // A NaN passed the range check, to be reported as a missing height on the first row.
  CHECK_THROWS_WITH(read_opencrg(path, std::nan("")),
                    Contains("road.crg: the track's lateral position v is not a finite number of metres"));
  // LDFI: 20 characters a value, 4 values a record, so a row of six goes on in a second record.
  const std::string ldfi = folder.write(
      "double.crg", replaced(opencrg(kCrgKeys, "", ""), "#:LRFI", "#:LDFI") +
                        "                   0                   0                   0                   0\n"
                        "               0.001               0.002\n"
                        "                   0                   0                   0                   0\n"
                        "               0.003               0.004\n");
  check_points(read_opencrg(ldfi, 0.0), {{0, 0.001}, {0.1, 0.003}}, 1e-15);
}

TEST_CASE("the public OpenCRG sample: its reference line and a track between two sections",
          "[contact][road_file][opencrg]") {
  const std::string path = std::string(TIREFE_SOURCE_DIR) + "/inputs/roads/handmade_straight.crg";
  const std::vector<Eigen::Vector2d> centre = read_opencrg(path, 0.0);
  REQUIRE(centre.size() == 23);
  CHECK(centre[1] == Eigen::Vector2d(1.0, 0.0111111));
  CHECK(centre[19] == Eigen::Vector2d(19.0, 0.0333333));
  CHECK(centre.back() == Eigen::Vector2d(22.0, 0.0));
  // Sections 5 and 6 are at v = 0.5 and 1.0 (7 sections, 0.5 m apart, from -1.5 m).
  CHECK(read_opencrg(path, 0.75)[19].y() == Approx(0.5 * (0.0222222 + 0.0111111)).epsilon(1e-14));
  CHECK_THROWS_WITH(read_opencrg(path, 1.25), Contains("handmade_straight.crg:85: no height at u = 7 m"));
}

TEST_CASE("OpenCRG errors name the file, the line and what to do", "[contact][road_file][opencrg]") {
  TempDir folder;
  const std::pair<std::string, std::string> cases[] = {
      {replaced(opencrg(kCrgKeys, "", kCrgData), "#:LRFI", "#:KRBI"),
       "bad.crg:8: the road data are binary (#:KRBI): tirefe reads the text formats LRFI and LDFI"},
      {replaced(opencrg(kCrgKeys, "", kCrgData), "#:LRFI\n", ""), "the road data are binary (#:KRBI)"},
      {opencrg(kCrgKeys, "$ROAD_CRG_MODS\nREFLINE_OFFSET_Z = 1\n$\n", kCrgData),
       "bad.crg:9: $ROAD_CRG_MODS: tirefe does not apply modifiers"},
      {opencrg(kCrgKeys + "REFERENCE_LINE_INCREMNT = 1\n", "", kCrgData),
       "bad.crg:7: $ROAD_CRG: unknown key REFERENCE_LINE_INCREMNT (did you mean 'REFERENCE_LINE_INCREMENT'?)"},
      {opencrg(kCrgKeys + "REFERENCE_LINE_START_SLOPE = 0.01\n", "", kCrgData),
       "bad.crg:7: $ROAD_CRG REFERENCE_LINE_START_SLOPE = 0.01: a banking or slope from start to end values is not"},
      {replaced(opencrg(kCrgKeys, "", kCrgData), "D:reference line phi,rad", "D:friction,-"),
       "bad.crg:10: channel 'D:friction,-': tirefe reads"},
      {opencrg(kCrgKeys, "", replaced(kCrgData, "0.0030000", "0.003O000")),
       "bad.crg:19: value 5 '0.003O000' is not a number (#:LRFI: 8 fields of 10 characters a line"},
      {opencrg(kCrgKeys, "", kCrgData + " 0.0000000\n"),
       "bad.crg:21: expected 6 values of 10 characters (#:LRFI), got ' 0.0000000'"},
      {opencrg(kCrgKeys, "", kCrgData.substr(0, kCrgData.find('\n') + 1)), "at least two rows of data"},
      {opencrg("LONG_SECTION_V_INCREMENT = 0.5\n", "", kCrgData), "$ROAD_CRG needs REFERENCE_LINE_INCREMENT"},
      {opencrg(kCrgKeys + "REFERENCE_LINE_END_U = 1\n", "", kCrgData),
       "bad.crg:7: $ROAD_CRG REFERENCE_LINE_END_U = 1, but 3 rows of REFERENCE_LINE_INCREMENT end at 0.2"},
      {replaced(opencrg(kCrgKeys, "", kCrgData), "$$$$$$$$$$\n", ""),
       "bad.crg:18: '0.0000000 0.0100000 0.0200000-0.0010000 0.0030000 0.0050000' outside a section ($CT, $ROAD_CRG, $KD_DEFINITION, ...; the road data follow a line of $$$$)"},
      {"[UNITS]\nLENGTH = 'meter'\n", "bad.crg:1: '[UNITS]' outside a section"},
      {"$CT\n$\n$KD_DEFINITION\n#:LRFI\nD:long section 1,m\n$\n", "bad.crg: no road data"},
  };
  for (const auto& [text, message] : cases) {
    INFO(text);
    CHECK_THROWS_WITH(read_opencrg(folder.write("bad.crg", text), 0.0), Contains(message));
  }
}

TEST_CASE("a profile file is read by its name, and one that is something else is refused as what it looks like",
          "[contact][road_file]") {
  TempDir folder;
  const std::pair<std::string, std::string> cases[] = {
      {opencrg(kCrgKeys, "", kCrgData), "road.txt: not two columns 'x y': the file looks like an OpenCRG file"},
      {"[MDI_HEADER]\nFILE_TYPE = 'rdf'\n",
       "looks like a road data file (TeimOrbit sections): give it the extension .rdf"},
      {"Distance (m);Height (m)\n0;0\n", "looks like a CSV file with a header: give it the extension .csv"},
      {"0 0\n1 oops\n", "road profile '" + folder.path("road.txt") + "', line 2: expected two numbers"},
  };
  for (const auto& [text, message] : cases) {
    INFO(text);
    CHECK_THROWS_WITH(read_road_profile(folder.write("road.txt", text), std::nullopt, std::nullopt), Contains(message));
  }
  check_points(read_road_profile(folder.write("road.txt", "0 0\n1e-3 2E-3\n"), std::nullopt, std::nullopt),
               {{0, 0}, {1e-3, 2e-3}});
  CHECK_THROWS_WITH(
      read_road_profile(folder.write("road.crg", opencrg(kCrgKeys, "", kCrgData)), RoadTrack::Left, std::nullopt),
      Contains("road.crg' has one track at each lateral position: give 'lateral' = v"));
  CHECK_THROWS_WITH(read_road_profile(folder.path("road.txt"), std::nullopt, 0.5),
                    Contains("'lateral' picks the track of an OpenCRG file (.crg)"));
}
