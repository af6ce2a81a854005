// Spindle forces in ISO 8855 wheel axes (tire/wheel_axes.hpp, docs/output.md "Axes and
// signs"): the conversion from the spindle's reaction, the built-in history and value
// quantities of a loaded tire for both headings, and the convention written into the file.
#include <catch2/catch.hpp>

#include <string>

#include "deck_support.hpp"
#include "io/hdf5_file.hpp"
#include "test_support.hpp"
#include "tire/wheel_axes.hpp"

using namespace tirefe;

TEST_CASE("wheel axes: forces the tire exerts on the wheel from the spindle's reaction", "[wheel_axes]") {
  // The axle pulls the wheel back (R_x < 0) and holds it down (R_y < 0) against a
  // clockwise moment: the tire pushes the wheel forward along +x, up, counter-clockwise.
  const Eigen::Vector3d reaction(-250.0, -3000.0, 40.0);
  const Eigen::Vector3d plus = wheel_load_from_reaction(reaction, Heading::PlusX);
  const Eigen::Vector3d minus = wheel_load_from_reaction(reaction, Heading::MinusX);
  CHECK(plus.x() == 250.0);    // along the heading +x: driving
  CHECK(minus.x() == -250.0);  // against the heading -x: braking
  CHECK(plus.y() == 3000.0);   // Fz up: the load, whatever the heading
  CHECK(minus.y() == 3000.0);
  CHECK(plus.z() == 40.0);  // y_ISO into the page: a counter-clockwise moment M_z = -40 is +40 about it
  CHECK(minus.z() == -40.0);
  // Rolling forward: clockwise toward +x, counter-clockwise toward -x.
  CHECK(wheel_spin_rate(-12.5, Heading::PlusX) == 12.5);
  CHECK(wheel_spin_rate(12.5, Heading::MinusX) == 12.5);
  Heading parsed = Heading::PlusX;
  CHECK(parse_heading("-x", parsed));
  CHECK(parsed == Heading::MinusX);
  CHECK_FALSE(parse_heading("forward", parsed));
}

TEST_CASE("wheel axes: motions and the Jacobian of the force in wheel axes", "[wheel_axes]") {
  for (const Heading heading : {Heading::PlusX, Heading::MinusX}) {
    const double h = heading_sign(heading);
    // Forward along the heading, up, and turned forward (clockwise seen heading +x).
    const Eigen::Vector3d wheel(0.3, -0.02, 1.5);
    CHECK(plane_motion(wheel, heading).isApprox(Eigen::Vector3d(h * 0.3, -0.02, -h * 1.5)));
    CHECK(plane_motion(plane_motion(wheel, heading), heading) == wheel);  // its own inverse
    // A reaction linear in the plane's motion, R = A q: the force in wheel axes is then
    // linear in the wheel motion, and its matrix is wheel_load_jacobian(A), column by column.
    Eigen::Matrix3d A;
    A << 1.0, 2.0, 3.0, -4.0, 5.0, -6.0, 7.0, -8.0, 9.0;
    const Eigen::Matrix3d J = wheel_load_jacobian(A, heading);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d unit = Eigen::Vector3d::Unit(j);
      const Eigen::Vector3d column = wheel_load_from_reaction(A * plane_motion(unit, heading), heading);
      CHECK((J.col(j) - column).norm() == 0.0);
    }
  }
}

namespace {

// Two small tires, one per heading, pressed 20 mm onto a flat road with friction and then
// pushed 2 mm along +x with the spin held: every reaction component is loaded.
const char* kLoadedTires = R"(
local function loaded_tire(heading)
  local model = tirefe.model{ title = "loaded tire, heading " .. heading }
  model:output{ file = "heading" .. heading .. ".h5" }
  local tp = require("tires.145SR12")
  tp.elements = 40
  tp.heading = heading
  local tire, level = require("tire_on_road").inflated(model, tp)
  model:surface{ name = "road", type = "flat", point = { 0, level } }
  model:contact{ surface = "road", set = tire.tread_set, friction = 0.8, history = "road" }
  model:load_function{ name = "press", points = { { 1, 0 }, { 2, 1 }, { 3, 1 } } }
  model:load_function{ name = "push", points = { { 2, 0 }, { 3, 1 } } }
  model:prescribe{ node = tire.spindle, dof = "uy", value = -0.02, load_function = "press" }
  model:prescribe{ node = tire.spindle, dof = "ux", value = 0.002, load_function = "push" }
  for _, c in ipairs{ "fx", "fz", "my" } do
    model:history{ name = "spindle_" .. c, node = tire.spindle, quantity = "spindle_force", component = c }
  end
  model:history{ name = "spin_rate", node = tire.spindle, quantity = "spin_rate" }
  model:solve{ to = 2.0, dt = 0.25 }
  local function wheel(c) return model:value{ node = tire.spindle, quantity = "spindle_force", component = c } end
  local function reaction(dof) return model:value{ node = tire.spindle, dof = dof, quantity = "reaction" } end
  -- Standing under load: Fz is the load, which the road carries (the contact's total force up).
  local road = model:contact_value{ name = "contact_road", quantity = "fy" }
  tirefe.check{ name = heading .. ": standing Fz = road's force on the tire [N]", value = wheel("fz"), expected = road,
                relative = 1e-6 }
  tirefe.check{ name = heading .. ": a 20 mm press carries 2.5-5 kN", value = wheel("fz"), expected = 3750, tolerance = 1250 }
  model:solve{ to = 3.0, dt = 0.25 }
  local h = heading == "+x" and 1 or -1
  tirefe.check{ name = heading .. ": Fx = -h R_x [N]", value = wheel("fx"), expected = -h * reaction("ux"), tolerance = 1e-9 }
  tirefe.check{ name = heading .. ": Fz = -R_y [N]", value = wheel("fz"), expected = -reaction("uy"), tolerance = 1e-9 }
  tirefe.check{ name = heading .. ": My = h M_z [N m]", value = wheel("my"), expected = h * reaction("rz"), tolerance = 1e-9 }
  tirefe.check{ name = heading .. ": the push loads Fx [N]", value = math.abs(wheel("fx")) > 100 and 1 or 0, expected = 1,
                tolerance = 0 }
  return { fx = wheel("fx"), fz = wheel("fz"), my = wheel("my"), rx = reaction("ux") }
end
local plus, minus = loaded_tire("+x"), loaded_tire("-x")
-- The same push seen from both headings: Fx and My change sign, Fz does not.
tirefe.check{ name = "Fx(+x) = -Fx(-x) [N]", value = plus.fx, expected = -minus.fx, relative = 1e-9 }
tirefe.check{ name = "My(+x) = -My(-x) [N m]", value = plus.my, expected = -minus.my, relative = 1e-9 }
tirefe.check{ name = "Fz(+x) = Fz(-x) [N]", value = plus.fz, expected = minus.fz, relative = 1e-9 }
-- The axle drags the wheel toward +x against the road's grip: the tire holds it back.
tirefe.check{ name = "heading +x: the grip retards the wheel, Fx < 0", value = plus.fx < 0 and 1 or 0, expected = 1,
              tolerance = 0 }
)";

}  // namespace

TEST_CASE("spindle_force and spin_rate: a loaded tire's forces in wheel axes for both headings, and the file says so",
          "[wheel_axes][macros]") {
  testing::TempDir folder;
  const std::string deck = folder.write("loaded.lua", kLoadedTires);
  testing::check_deck_passes(deck, folder.path(), 2 * 6 + 4);

  for (const std::string heading : {"+x", "-x"}) {
    INFO("heading " << heading);
    const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("heading" + heading + ".h5"));
    CHECK(file.read_string_attribute("/", "axes") ==
          "ISO 8855 wheel axes (C): x heading, y left, z up; forces the tire exerts on the wheel");
    CHECK(file.read_string_attribute("/", "heading") == heading);
    CHECK(file.read_string_attribute("/history/spindle_fx", "unit") == "N");
    CHECK(file.read_string_attribute("/history/spindle_fz", "unit") == "N");
    CHECK(file.read_string_attribute("/history/spindle_my", "unit") == "N m");
    CHECK(file.read_string_attribute("/history/spin_rate", "unit") == "rad/s");
    // The channel's last row is the pushed state the deck compared with the reactions;
    // standing pressed, the load is up.
    const std::vector<double> fz = file.read_doubles("/history/spindle_fz");
    const std::vector<double> time = file.read_doubles("/history/time");
    REQUIRE(fz.size() == time.size());
    for (size_t i = 0; i < time.size(); ++i)
      if (time[i] > 1.5) CHECK(fz[i] > 1000.0);
    CHECK(file.read_doubles("/history/spin_rate").back() == 0.0);  // the spin is held
  }
}

TEST_CASE("every result file states the spindle forces' axes, a tire's file its heading", "[wheel_axes][output]") {
  testing::TempDir folder;
  const std::string deck = folder.write("beam.lua", R"(
local model = tirefe.model{ title = "no tire" }
local a, b = model:node{ x = 0, y = 0 }, model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e6, GA = 1e6, EI = 10 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:load{ node = b, fy = -1 }
model:output{ file = "beam.h5" }
model:solve{ to = 1.0, dt = 1.0 }
)");
  testing::check_deck_passes(deck, folder.path(), 0);
  const io::Hdf5File file = io::Hdf5File::open_read_only(folder.path("beam.h5"));
  CHECK(file.read_string_attribute("/", "axes") == wheel_axes_statement());
  CHECK_THROWS(file.read_string_attribute("/", "heading"));  // no tire, no heading
}
