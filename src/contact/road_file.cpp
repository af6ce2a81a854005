#include "contact/road_file.hpp"

#include <cctype>
#include <cmath>

#include "core/mesh.hpp"
#include "fitting/curve_data.hpp"
#include "io/teim_orbit.hpp"

namespace tirefe {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr io::Dimension kLength{1};
constexpr io::Dimension kAngle{0, 0, 0, 0, 1};
constexpr const char* kParameters = "PARAMETERS";

std::string number_text(double value) { return io::round_trip_number(value); }

/// Appends a point of a track, skipping a repeat of the last one; the problem otherwise.
std::optional<std::string> append_point(std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& point) {
  if (!points.empty() && point == points.back()) return std::nullopt;
  if (!points.empty() && point.x() < points.back().x())
    return "x = " + number_text(point.x()) + " m comes after x = " + number_text(points.back().x()) +
           " m (x must not decrease)";
  points.push_back(point);
  return std::nullopt;
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

/// The keys of one road type in [PARAMETERS]. Each type reads all its keys first and then
/// calls all_read(), so that a misspelt key is reported as unknown rather than as missing.
class RoadParameters {
 public:
  explicit RoadParameters(io::TeimOrbitReader& reader) : reader_(reader) {}
  std::optional<double> number(const char* key, const io::Dimension& dimension = kLength) {
    return reader_.number(kParameters, key, dimension);
  }
  void all_read() const { reader_.finish(); }
  double required(const char* key, const std::optional<double>& value, const std::string& meaning) const {
    if (!value) fail(key, "missing [PARAMETERS] " + std::string(key) + " (" + meaning + ")");
    return *value;
  }
  [[noreturn]] void fail(const char* key, const std::string& message) const {
    const int line = reader_.line(kParameters, key);
    const io::TeimOrbitSection* section = reader_.file().section(kParameters);
    reader_.fail(line ? line : section ? section->line : 0, message);
  }
  void require(bool condition, const char* key, const std::string& message) const {
    if (!condition) fail(key, std::string("[PARAMETERS] ") + key + " " + message);
  }
  io::TeimOrbitReader& reader() { return reader_; }

 private:
  io::TeimOrbitReader& reader_;
};

/// The corners of an obstacle (in order along x) raised by the road's offset.
std::vector<Eigen::Vector2d> profile_of(const std::vector<Eigen::Vector2d>& corners, double offset) {
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector2d& corner : corners) append_point(points, corner + Eigen::Vector2d(0.0, offset));
  return points;
}

struct Obstacle {
  double size, start, length;
};

/// An obstacle across the road: its size key (HEIGHT or DEPTH, not 0), START, LENGTH (> 0)
/// and DIRECTION, which must be 0: an obstacle at an angle to the road meets the left and
/// right wheels at different places. 'more' reads the type's other keys.
template <class More>
Obstacle read_obstacle(RoadParameters& parameters, const char* size_key, const std::string& size_meaning, More&& more) {
  const auto size = parameters.number(size_key), start = parameters.number("START");
  const auto length = parameters.number("LENGTH");
  const double direction = parameters.number("DIRECTION", kAngle).value_or(0.0);
  more();
  parameters.all_read();
  const Obstacle obstacle{parameters.required(size_key, size, size_meaning),
                          parameters.required("START", start, "where it begins along x"),
                          parameters.required("LENGTH", length, "its length along x")};
  parameters.require(direction == 0.0, "DIRECTION",
                     "must be 0: an obstacle at an angle to the road meets the left and right wheels at different "
                     "places (in the plane model, place each track's obstacle with 'start')");
  parameters.require(obstacle.size != 0.0, size_key, "must not be 0");
  parameters.require(obstacle.length > 0.0, "LENGTH", "must be positive (got " + number_text(obstacle.length) + " m)");
  return obstacle;
}

std::vector<Eigen::Vector2d> plank(RoadParameters& parameters, double offset) {
  double bevel = 0.0;
  const auto [height, start, length] =
      read_obstacle(parameters, "HEIGHT", "height of the plank; negative: a groove",
                    [&] { bevel = parameters.number("BEVEL_EDGE_LENGTH").value_or(0.0); });
  parameters.require(bevel >= 0.0 && bevel <= std::abs(height), "BEVEL_EDGE_LENGTH",
                     "must be between 0 and the plank's height (got " + number_text(bevel) + " m)");
  parameters.require(2.0 * bevel <= length, "BEVEL_EDGE_LENGTH",
                     "must be at most half the plank's LENGTH (got " + number_text(bevel) + " m)");
  // 45 degree bevels: the edge drops by as much as it runs.
  const double shoulder = height - std::copysign(bevel, height);
  return profile_of({{start, 0.0},
                     {start, shoulder},
                     {start + bevel, height},
                     {start + length - bevel, height},
                     {start + length, shoulder},
                     {start + length, 0.0}},
                    offset);
}

std::vector<Eigen::Vector2d> pot_hole(RoadParameters& parameters, double offset) {
  const auto [depth, start, length] = read_obstacle(parameters, "DEPTH", "depth of the hole; negative: a bump", [] {});
  return profile_of({{start, 0.0}, {start, -depth}, {start + length, -depth}, {start + length, 0.0}}, offset);
}

std::vector<Eigen::Vector2d> poly_line(RoadParameters& parameters, double offset, std::optional<RoadTrack> track) {
  io::TeimOrbitReader& reader = parameters.reader();
  const io::TeimOrbitTable* data = reader.table(kParameters, "XZ_DATA");
  parameters.all_read();
  if (!data) parameters.fail("", "a poly_line road needs its profile as an (XZ_DATA) table in [PARAMETERS]");
  const size_t width = !data->columns.empty() ? data->columns.size() : data->rows.empty() ? 0 : data->rows[0].size();
  if (width < 2 || width > 4)
    reader.fail(data->line, "(XZ_DATA) has " + std::to_string(width) +
                                " columns: give 2 (x z), 3 (x z_l z_r) or 4 (x_l z_l x_r z_r)");
  if (width > 2 && !track)
    reader.fail(data->line, "(XZ_DATA) holds a left and a right track: give track = \"left\" or \"right\"");
  const bool left = width == 2 || *track == RoadTrack::Left;
  std::vector<Eigen::Vector2d> points;
  for (size_t row = 0; row < data->rows.size(); ++row) {
    const std::vector<double> values = reader.row_numbers(*data, row, kLength);
    if (values.size() != width)
      reader.fail(data->row_lines[row],
                  "(XZ_DATA) row has " + std::to_string(values.size()) + " values, expected " + std::to_string(width));
    const double x = width == 4 && !left ? values[2] : values[0];
    const double z = width == 2 || left ? values[1] : values[width - 1];
    if (const auto problem = append_point(points, {x, z + offset}))
      reader.fail(data->row_lines[row], "(XZ_DATA), " + std::string(left ? "left" : "right") + " track: " + *problem);
  }
  if (points.size() < 2) reader.fail(data->line, "(XZ_DATA) needs at least two distinct points");
  return points;
}

RoadShape drum(RoadParameters& parameters, double offset) {
  const auto diameter = parameters.number("DIAMETER");
  const double cleats = parameters.number("NUMBER_CLEATS", {}).value_or(0.0);
  const auto height = parameters.number("CLEAT_HEIGHT");
  const auto length = parameters.number("CLEAT_LENGTH");
  const auto angle = parameters.number("CLEAT_STARTING_ANGLE", kAngle);
  const double bevel = parameters.number("CLEAT_BEVEL_EDGE_LENGTH").value_or(0.0);
  const double rounded = parameters.number("CLEAT_EDGE_ROUNDED", {}).value_or(0.0);
  const double curved = parameters.number("CURVED_CLEAT_SURFACE", {}).value_or(1.0);
  parameters.all_read();
  RoadShape shape;
  shape.kind = RoadShape::Kind::Drum;
  shape.diameter = parameters.required("DIAMETER", diameter, "diameter of the drum");
  parameters.require(shape.diameter > 0.0, "DIAMETER", "must be positive");
  parameters.require(offset == 0.0, "OFFSET", "must be 0 for a drum: the deck's 'centre' places it");
  parameters.require(cleats == 0.0 || cleats == 1.0, "NUMBER_CLEATS", "must be 0 or 1 (a drum carries one cleat)");
  if (cleats == 0.0) {
    parameters.require(!height && !length && !angle, "NUMBER_CLEATS", "is 0, but the file describes a cleat");
    return shape;
  }
  if (!height || !length || !angle)
    parameters.fail("NUMBER_CLEATS",
                    "a cleat needs CLEAT_HEIGHT, CLEAT_LENGTH (along the drum surface) and "
                    "CLEAT_STARTING_ANGLE (its middle, from the drum's top)");
  parameters.require(*height > 0.0, "CLEAT_HEIGHT", "must be positive");
  parameters.require(*length > 0.0, "CLEAT_LENGTH", "must be positive");
  parameters.require(rounded == 0.0 || rounded == 1.0, "CLEAT_EDGE_ROUNDED", "must be 0 or 1");
  parameters.require(bevel >= 0.0, "CLEAT_BEVEL_EDGE_LENGTH", "must not be negative");
  parameters.require(bevel == 0.0 || rounded == 1.0, "CLEAT_BEVEL_EDGE_LENGTH",
                     "> 0 with flat bevels is not modelled on a drum: CLEAT_EDGE_ROUNDED = 1 rounds the edges with "
                     "a quarter circle of that radius");
  parameters.require(curved == 1.0, "CURVED_CLEAT_SURFACE",
                     "must be 1: the cleat's top is an arc concentric with the drum (a flat top is not modelled)");
  shape.cleat.height = *height;
  shape.cleat.arc_length = *length;
  shape.cleat.angle = 0.5 * kPi + *angle;  // from the top (where a tire above the drum stands), counter-clockwise
  shape.cleat.edge_radius = bevel;
  return shape;
}

}  // namespace

RoadShape read_road_data_file(const std::string& path, std::optional<RoadTrack> track) {
  const io::TeimOrbitFile file = io::TeimOrbitFile::read(path);
  io::TeimOrbitReader reader(file, "rdf");
  const io::TeimOrbitSection* model = file.section("MODEL");
  const int model_line = model ? model->line : 0;
  const auto method = reader.string("MODEL", "METHOD");
  if (!method || !io::same_name(*method, "2D"))
    reader.fail(method ? reader.line("MODEL", "METHOD") : model_line,
                "[MODEL] needs METHOD = '2D': tirefe reads the 2D roads of road data files");
  const auto type = reader.string("MODEL", "ROAD_TYPE");
  if (!type) reader.fail(model_line, "[MODEL] has no ROAD_TYPE (flat, poly_line, plank, pot_hole or drum)");
  reader.string("MODEL", "FUNCTION_NAME");  // the road routine of the program that wrote the file

  RoadParameters parameters(reader);
  const double offset = parameters.number("OFFSET").value_or(0.0);
  parameters.require(parameters.number("ROTATION_ANGLE_XY_PLANE", kAngle).value_or(0.0) == 0.0,
                     "ROTATION_ANGLE_XY_PLANE", "must be 0: the plane model's road runs along +x");
  parameters.require(parameters.number("MU", {}).value_or(1.0) == 1.0, "MU",
                     "must be 1: the friction coefficient is the contact's (model:contact{ friction = ... })");

  RoadShape shape;
  const std::string road_type = lower(*type);
  if (road_type == "flat") {
    parameters.all_read();
    shape.kind = RoadShape::Kind::Flat;
    shape.level = offset;
  } else if (road_type == "poly_line") {
    shape.points = poly_line(parameters, offset, track);
  } else if (road_type == "plank") {
    shape.points = plank(parameters, offset);
  } else if (road_type == "pot_hole") {
    shape.points = pot_hole(parameters, offset);
  } else if (road_type == "drum") {
    shape = drum(parameters, offset);
  } else {
    reader.fail(reader.line("MODEL", "ROAD_TYPE"), "[MODEL] ROAD_TYPE = '" + *type +
                                                       "': tirefe reads the 2D road types flat, poly_line, plank, "
                                                       "pot_hole and drum");
  }
  shape.road_type = road_type;
  return shape;
}

std::vector<Eigen::Vector2d> read_road_csv(const std::string& path, std::optional<RoadTrack> track) {
  const fitting::CurveData data = fitting::CurveData::read_csv(path);
  const fitting::DataColumn *x = nullptr, *z = nullptr, *left = nullptr, *right = nullptr;
  for (const fitting::DataColumn& column : data.columns()) {
    const std::string& name = column.name;
    const fitting::DataColumn** slot = name == "x" || name == "distance"             ? &x
                                       : name == "z" || name == "height"             ? &z
                                       : name == "z_left" || name == "height_left"   ? &left
                                       : name == "z_right" || name == "height_right" ? &right
                                                                                     : nullptr;
    if (!slot)
      throw ModelError(path + ": column '" + column.header +
                       "' is not part of a road profile (x or distance; z or height, or z_left and z_right)");
    if (*slot) throw ModelError(path + ": columns '" + (*slot)->header + "' and '" + column.header + "' say the same");
    if (!column.si_unit.empty() && column.si_unit != "m")
      throw ModelError(path + ": column '" + column.header + "' is in " + column.si_unit + ", not a length");
    *slot = &column;
  }
  if (!x) throw ModelError(path + ": no position column (x or distance, e.g. x_m)");
  if (z ? left || right : !left || !right)
    throw ModelError(path + ": give one height column (z or height) or one per track (z_left and z_right)");
  if (!z && !track)
    throw ModelError(path + ": the file holds a left and a right track: give track = \"left\" or \"right\"");
  const fitting::DataColumn& height = z ? *z : *track == RoadTrack::Left ? *left : *right;
  std::vector<Eigen::Vector2d> points;
  for (size_t row = 0; row < data.rows(); ++row)
    if (const auto problem = append_point(points, {x->values[row], height.values[row]}))
      throw ModelError(path + ":" + std::to_string(data.line(row)) + ": " + *problem);
  if (points.size() < 2) throw ModelError(path + ": a road profile needs at least two distinct points");
  return points;
}

}  // namespace tirefe
