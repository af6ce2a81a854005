#include "formats/road_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include "core/mesh.hpp"
#include "core/spelling.hpp"
#include "fitting/curve_data.hpp"
#include "formats/teim_orbit.hpp"

namespace tirefe {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr formats::Dimension kLength{1};
constexpr formats::Dimension kAngle{0, 0, 0, 0, 1};
constexpr const char* kParameters = "PARAMETERS";

std::string number_text(double value) { return formats::round_trip_number(value); }

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
  explicit RoadParameters(formats::TeimOrbitReader& reader) : reader_(reader) {}
  std::optional<double> number(const char* key, const formats::Dimension& dimension = kLength) {
    return reader_.number(kParameters, key, dimension);
  }
  void all_read() const { reader_.finish(); }
  double required(const char* key, const std::optional<double>& value, const std::string& meaning) const {
    if (!value) fail(key, "missing [PARAMETERS] " + std::string(key) + " (" + meaning + ")");
    return *value;
  }
  [[noreturn]] void fail(const char* key, const std::string& message) const {
    const int line = reader_.line(kParameters, key);
    const formats::TeimOrbitSection* section = reader_.file().section(kParameters);
    reader_.fail(line ? line : section ? section->line : 0, message);
  }
  void require(bool condition, const char* key, const std::string& message) const {
    if (!condition) fail(key, std::string("[PARAMETERS] ") + key + " " + message);
  }
  formats::TeimOrbitReader& reader() { return reader_; }

 private:
  formats::TeimOrbitReader& reader_;
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
  formats::TeimOrbitReader& reader = parameters.reader();
  const formats::TeimOrbitTable* data = reader.table(kParameters, "XZ_DATA");
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
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::read(path);
  formats::TeimOrbitReader reader(file, "rdf");
  const formats::TeimOrbitSection* model = file.section("MODEL");
  const int model_line = model ? model->line : 0;
  const auto method = reader.string("MODEL", "METHOD");
  if (!method || !formats::same_name(*method, "2D"))
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
  const auto one_of = [](const std::string& name, std::initializer_list<const char*> names) {
    return std::any_of(names.begin(), names.end(), [&](const char* known) { return name == known; });
  };
  for (const fitting::DataColumn& column : data.columns()) {
    const std::string name = lower(column.name);
    const fitting::DataColumn** slot = one_of(name, {"x", "s", "distance"})                           ? &x
                                       : one_of(name, {"z", "height", "elevation"})                   ? &z
                                       : one_of(name, {"z_left", "height_left", "elevation_left"})    ? &left
                                       : one_of(name, {"z_right", "height_right", "elevation_right"}) ? &right
                                                                                                      : nullptr;
    if (!slot)
      throw ModelError(path + ": column '" + column.header +
                       "' is not part of a road profile (x, s or distance; z, height or elevation, or one per track: "
                       "z_left and z_right)");
    if (*slot) throw ModelError(path + ": columns '" + (*slot)->header + "' and '" + column.header + "' say the same");
    if (!column.si_unit.empty() && column.si_unit != "m")
      throw ModelError(path + ": column '" + column.header + "' is in " + column.si_unit + ", not a length");
    *slot = &column;
  }
  if (!x) throw ModelError(path + ": no position column (x, s or distance, e.g. x_m or 'Distance (m)')");
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

// ---- OpenCRG ----------------------------------------------------------------------

namespace {

/// One data channel of an OpenCRG file's $KD_Definition.
struct CrgChannel {
  enum class Kind { Heading, Banking, Slope, Section } kind;
  std::optional<double> v;  // a section's lateral position, given or from its number
  int number = 0;           // "long section N" (0: given by "at v = X")
  int line = 0;
};

using formats::trimmed;
using formats::upper;

std::optional<double> crg_number(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789+-.eEdD") != std::string::npos) return std::nullopt;
  std::string c_text = text;
  std::replace(c_text.begin(), c_text.end(), 'D', 'E');  // FORTRAN's double exponent
  std::replace(c_text.begin(), c_text.end(), 'd', 'e');
  char* end = nullptr;
  const double value = std::strtod(c_text.c_str(), &end);
  if (end != c_text.c_str() + c_text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// The $ROAD_CRG keys: those the plane model reads, and those it passes over (the
/// reference line's place and heading in the x-y plane, which a track along u does not
/// need). Grid banking and slope from start to end values are not modelled.
const char* const kCrgUsedKeys[] = {"REFERENCE_LINE_START_U", "REFERENCE_LINE_END_U",   "REFERENCE_LINE_INCREMENT",
                                    "LONG_SECTION_V_RIGHT",   "LONG_SECTION_V_LEFT",    "LONG_SECTION_V_INCREMENT",
                                    "REFERENCE_LINE_START_Z", "REFERENCE_LINE_OFFSET_Z"};
const char* const kCrgPlacementKeys[] = {
    "REFERENCE_LINE_START_X",  "REFERENCE_LINE_START_Y",   "REFERENCE_LINE_START_PHI", "REFERENCE_LINE_END_X",
    "REFERENCE_LINE_END_Y",    "REFERENCE_LINE_END_PHI",   "REFERENCE_LINE_END_Z",     "REFERENCE_LINE_OFFSET_X",
    "REFERENCE_LINE_OFFSET_Y", "REFERENCE_LINE_OFFSET_PHI"};
const char* const kCrgGridSlopeKeys[] = {"REFERENCE_LINE_START_BANK", "REFERENCE_LINE_END_BANK",
                                         "REFERENCE_LINE_START_SLOPE", "REFERENCE_LINE_END_SLOPE"};

class OpenCrgFile {
 public:
  explicit OpenCrgFile(const std::string& path) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ModelError(path + ": cannot open the file");
    read_header(in);
    read_data(in);
  }

  std::vector<Eigen::Vector2d> track(double v) const;

 private:
  enum class Section { None, Comment, Road, Definition, Skipped, Modifiers, Files };

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw ModelError(path_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message);
  }
  void read_header(std::istream& in);
  void read_road_key(const std::string& text, int line);
  void read_channel(const std::string& text, int line);
  void read_data(std::istream& in);
  std::optional<double> key(const char* name) const {
    const auto found = keys_.find(name);
    return found == keys_.end() ? std::nullopt : std::optional<double>(found->second.first);
  }

  std::string path_;
  int line_ = 0;                                        // the last line read
  int definition_line_ = 0;                             // of $KD_Definition
  std::map<std::string, std::pair<double, int>> keys_;  // $ROAD_CRG: value, line
  std::string format_;                                  // LRFI or LDFI
  std::vector<CrgChannel> channels_;
  std::vector<std::vector<double>> rows_;  // one per u, one value per channel (NaN: missing)
  std::vector<int> row_lines_;
};

void OpenCrgFile::read_header(std::istream& in) {
  Section section = Section::None;
  std::string raw;
  while (std::getline(in, raw)) {
    ++line_;
    for (const char c : raw)
      if (c == '\0' || (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r'))
        fail(line_, "a NUL or control byte in the header: the file is damaged or not an OpenCRG file");
    const std::string line = trimmed(raw);
    if (line.rfind("$$", 0) == 0) {           // the end of the header: the road data follow
      if (format_.empty()) format_ = "KRBI";  // the format of a file that names none
      if (format_ != "LRFI" && format_ != "LDFI")
        fail(definition_line_, "the road data are binary (#:" + format_ +
                                   "): tirefe reads the text formats LRFI and LDFI (write the file as text with "
                                   "the OpenCRG tools)");
      return;
    }
    if (!line.empty() && line.front() == '$') {
      const std::string keyword =
          upper(trimmed(line.substr(1, line.find('!') == std::string::npos ? std::string::npos : line.find('!') - 1)));
      if (keyword.empty())
        section = Section::None;  // "$" closes a section
      else if (keyword == "CT")
        section = Section::Comment;
      else if (keyword == "ROAD_CRG")
        section = Section::Road;
      else if (keyword == "KD_DEFINITION")
        section = Section::Definition, definition_line_ = line_;
      else if (keyword == "ROAD_CRG_OPTS" || keyword == "ROAD_CRG_MPRO")
        section = Section::Skipped;
      else if (keyword == "ROAD_CRG_MODS")
        section = Section::Modifiers;
      else if (keyword == "ROAD_CRG_FILE")
        section = Section::Files;
      else
        fail(line_, "unknown section $" + keyword +
                        " (an OpenCRG header has $CT, $ROAD_CRG, $ROAD_CRG_OPTS, $ROAD_CRG_MODS, $ROAD_CRG_MPRO, "
                        "$ROAD_CRG_FILE and $KD_DEFINITION, then a line of $$$$ before the data)");
      continue;
    }
    if (section == Section::Comment) continue;
    const std::string content = trimmed(line.substr(0, line.find('!')));
    if (content.empty() || content.front() == '*') continue;  // a comment line
    switch (section) {
      case Section::Road: read_road_key(content, line_); break;
      case Section::Definition: read_channel(content, line_); break;
      case Section::Skipped: break;  // evaluation options and map projection: not needed along one track
      case Section::Modifiers:
        fail(line_,
             "$ROAD_CRG_MODS: tirefe does not apply modifiers to the data (apply them with the OpenCRG "
             "tools and write the file again)");
      case Section::Files: fail(line_, "$ROAD_CRG_FILE: tirefe reads one file, not the files it refers to");
      default:
        fail(line_, "'" + content +
                        "' outside a section ($CT, $ROAD_CRG, $KD_DEFINITION, ...; the road data follow a line of "
                        "$$$$)");
    }
  }
  fail(0, "no road data: an OpenCRG file holds a header of $ sections, a line of $$$$, then the data");
}

void OpenCrgFile::read_road_key(const std::string& text, int line) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos) fail(line, "$ROAD_CRG: expected KEY = value, got '" + text + "'");
  const std::string name = upper(trimmed(text.substr(0, equals))), value_text = trimmed(text.substr(equals + 1));
  const auto value = crg_number(value_text);
  if (!value) fail(line, "$ROAD_CRG " + name + " = " + value_text + ": not a finite number");
  if (keys_.count(name))
    fail(line, "$ROAD_CRG " + name + " is given twice (first at line " + std::to_string(keys_[name].second) + ")");
  std::vector<std::string> known;
  for (const char* key : kCrgUsedKeys) known.push_back(key);
  for (const char* key : kCrgPlacementKeys) known.push_back(key);
  for (const char* key : kCrgGridSlopeKeys) {
    known.push_back(key);
    if (name == key && *value != 0.0)
      fail(line, "$ROAD_CRG " + name + " = " + value_text +
                     ": a banking or slope from start to end values is not modelled (give it as a data channel, "
                     "D:reference line banking or slope)");
  }
  if (std::find(known.begin(), known.end(), name) == known.end()) {
    const std::string hint = did_you_mean(name, known);
    fail(line, "$ROAD_CRG: unknown key " + name + (hint.empty() ? "" : " (" + hint + ")"));
  }
  keys_[name] = {*value, line};
}

void OpenCrgFile::read_channel(const std::string& text, int line) {
  const std::string head = upper(text.substr(0, 2));
  if (head == "#:") {
    format_ = upper(trimmed(text.substr(2)));
    if (format_ != "LRFI" && format_ != "LDFI" && format_ != "KRBI" && format_ != "KDBI")
      fail(line, "unknown data format #:" + format_ + " (LRFI, LDFI, KRBI or KDBI)");
    return;
  }
  if (head == "U:") return;  // a virtual channel: no column of the data
  if (head != "D:") fail(line, "$KD_DEFINITION: expected #:FORMAT, D:channel,unit or U:channel, got '" + text + "'");
  const std::string definition = upper(trimmed(text.substr(2)));
  const std::string name = trimmed(definition.substr(0, definition.find(',')));
  CrgChannel channel{CrgChannel::Kind::Section, std::nullopt, 0, line};
  if (name == "REFERENCE LINE PHI") {
    channel.kind = CrgChannel::Kind::Heading;
  } else if (name == "REFERENCE LINE BANKING") {
    channel.kind = CrgChannel::Kind::Banking;
  } else if (name == "REFERENCE LINE SLOPE") {
    channel.kind = CrgChannel::Kind::Slope;
  } else if (name.rfind("LONG SECTION AT V", 0) == 0) {
    const size_t equals = name.find('=');
    const auto v = equals == std::string::npos ? std::nullopt : crg_number(trimmed(name.substr(equals + 1)));
    if (!v) fail(line, "expected D:long section at v = X,m (X the lateral position in m), got '" + text + "'");
    channel.v = *v;
  } else if (name.rfind("LONG SECTION", 0) == 0) {
    const auto number = crg_number(trimmed(name.substr(12)));
    if (!number || *number < 1 || *number != std::floor(*number) || *number > 1e6)
      fail(line, "expected D:long section N,m (N = 1, 2, ... from the right), got '" + text + "'");
    channel.number = static_cast<int>(*number);
  } else {
    fail(line, "channel '" + text +
                   "': tirefe reads the channels reference line phi, banking and slope and the long sections (D:long "
                   "section N,m or D:long section at v = X,m)");
  }
  if (channel.kind == CrgChannel::Kind::Section && definition.find(",M") == std::string::npos)
    fail(line, "channel '" + text + "': a long section holds heights in m (D:long section 1,m)");
  channels_.push_back(channel);
}

void OpenCrgFile::read_data(std::istream& in) {
  if (channels_.empty()) fail(definition_line_, "$KD_DEFINITION defines no channel (D:long section 1,m, ...)");
  const size_t width = format_ == "LRFI" ? 10 : 20, per_record = 80 / width;
  std::string raw;
  std::vector<double> row;
  while (std::getline(in, raw)) {
    ++line_;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    if (trimmed(raw).empty()) continue;
    if (row.empty()) row_lines_.push_back(line_);
    // A row starts in a new record; one of more channels than a record holds goes on in the next.
    const size_t fields = std::min(per_record, channels_.size() - row.size());
    if (raw.size() < (fields - 1) * width + 1)
      fail(line_, "expected " + std::to_string(fields) + " values of " + std::to_string(width) +
                      " characters (#:" + format_ + "), got '" + raw + "'");
    for (size_t i = 0; i < fields; ++i) {
      const std::string field = trimmed(raw.substr(i * width, width));
      if (!field.empty() && field.front() == '*') {  // a missing value
        row.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      const auto value = crg_number(field);
      if (!value)
        fail(line_, "value " + std::to_string(i + 1) + " '" + field + "' is not a number (#:" + format_ + ": " +
                        std::to_string(per_record) + " fields of " + std::to_string(width) +
                        " characters a line; '*' for a missing value)");
      row.push_back(*value);
    }
    if (raw.size() > fields * width && !trimmed(raw.substr(fields * width)).empty())
      fail(line_, "more values than the " + std::to_string(channels_.size()) + " channels of $KD_DEFINITION");
    if (row.size() == channels_.size()) rows_.push_back(std::move(row)), row.clear();
  }
  if (!row.empty())
    fail(line_,
         "the last row holds " + std::to_string(row.size()) + " of " + std::to_string(channels_.size()) + " values");
  if (rows_.size() < 2) fail(line_, "an OpenCRG road needs at least two rows of data");
}

std::vector<Eigen::Vector2d> OpenCrgFile::track(double v) const {
  const size_t rows = rows_.size();
  // The reference line's grid along u.
  const double start = key("REFERENCE_LINE_START_U").value_or(0.0);
  const auto end = key("REFERENCE_LINE_END_U");
  auto increment = key("REFERENCE_LINE_INCREMENT");
  if (!increment && !end) fail(0, "$ROAD_CRG needs REFERENCE_LINE_INCREMENT (or REFERENCE_LINE_END_U)");
  if (!increment) increment = (*end - start) / static_cast<double>(rows - 1);
  if (!(*increment > 0.0)) fail(0, "$ROAD_CRG: the reference line's increment must be positive");
  if (end && std::abs(start + *increment * static_cast<double>(rows - 1) - *end) > 1e-6 * std::max(1.0, std::abs(*end)))
    fail(keys_.at("REFERENCE_LINE_END_U").second,
         "$ROAD_CRG REFERENCE_LINE_END_U = " + number_text(*end) + ", but " + std::to_string(rows) +
             " rows of REFERENCE_LINE_INCREMENT end at " + number_text(start + *increment * double(rows - 1)));

  // The lateral positions of the long sections: given, or from their numbers and the grid.
  std::vector<std::pair<double, size_t>> sections;  // v, channel
  size_t numbered = 0;
  for (const CrgChannel& channel : channels_) numbered += channel.number > 0;
  const auto v_increment = key("LONG_SECTION_V_INCREMENT");
  const auto v_right = key("LONG_SECTION_V_RIGHT"), v_left = key("LONG_SECTION_V_LEFT");
  for (size_t c = 0; c < channels_.size(); ++c) {
    const CrgChannel& channel = channels_[c];
    if (channel.kind != CrgChannel::Kind::Section) continue;
    double section_v = 0.0;
    if (channel.v) {
      section_v = *channel.v;
    } else {
      const double count = static_cast<double>(numbered);
      const double step = v_increment                         ? *v_increment
                          : v_right && v_left && numbered > 1 ? (*v_left - *v_right) / (count - 1.0)
                                                              : 0.0;
      if (!(step > 0.0))
        fail(channel.line, "numbered long sections need LONG_SECTION_V_INCREMENT (or V_RIGHT and V_LEFT) in $ROAD_CRG");
      const double right = v_right ? *v_right : v_left ? *v_left - (count - 1.0) * step : -0.5 * (count - 1.0) * step;
      section_v = right + (channel.number - 1) * step;
    }
    sections.push_back({section_v, c});
  }
  if (sections.empty()) fail(definition_line_, "$KD_DEFINITION defines no long section (D:long section 1,m, ...)");
  std::sort(sections.begin(), sections.end());
  for (size_t i = 1; i < sections.size(); ++i)
    if (sections[i].first == sections[i - 1].first)
      fail(channels_[sections[i].second].line, "two long sections at v = " + number_text(sections[i].first) + " m");
  if (!std::isfinite(v)) fail(0, "the track's lateral position v is not a finite number of metres");
  const double tolerance = 1e-9 * std::max(1.0, std::abs(v));
  if (v < sections.front().first - tolerance || v > sections.back().first + tolerance)
    fail(definition_line_,
         "the track's lateral position v = " + number_text(v) + " m lies outside the road's long sections (v from " +
             number_text(sections.front().first) + " to " + number_text(sections.back().first) + " m)");
  size_t right = 0;
  while (right + 1 < sections.size() && sections[right + 1].first <= v + tolerance) ++right;
  const size_t left = std::min(right + 1, sections.size() - 1);
  const double weight = left == right || std::abs(v - sections[right].first) <= tolerance
                            ? 0.0
                            : (v - sections[right].first) / (sections[left].first - sections[right].first);

  const auto channel_of = [&](CrgChannel::Kind kind) -> std::optional<size_t> {
    for (size_t c = 0; c < channels_.size(); ++c)
      if (channels_[c].kind == kind) return c;
    return std::nullopt;
  };
  const auto slope = channel_of(CrgChannel::Kind::Slope), banking = channel_of(CrgChannel::Kind::Banking);
  double reference = key("REFERENCE_LINE_START_Z").value_or(0.0) + key("REFERENCE_LINE_OFFSET_Z").value_or(0.0);
  std::vector<Eigen::Vector2d> points;
  for (size_t i = 0; i < rows; ++i) {
    const std::vector<double>& row = rows_[i];
    const auto missing = [&](const std::string& what) {
      fail(row_lines_[i], "no " + what + " at u = " + number_text(start + *increment * double(i)) +
                              " m (a missing value): the track at v = " + number_text(v) +
                              " m needs one on every row (choose a v where the road has data)");
    };
    // The slope of row i leads from row i - 1 to it (the first row's is not used).
    if (slope && i > 0) {
      if (std::isnan(row[*slope])) missing("slope");
      reference += row[*slope] * *increment;
    }
    double z =
        (1.0 - weight) * row[sections[right].second] + (weight > 0.0 ? weight * row[sections[left].second] : 0.0);
    if (std::isnan(z)) missing("height");
    if (banking && v != 0.0) {
      if (std::isnan(row[*banking])) missing("banking");
      z += row[*banking] * v;
    }
    const Eigen::Vector2d point(start + *increment * static_cast<double>(i), reference + z);
    if (const auto problem = append_point(points, point)) fail(row_lines_[i], *problem);
  }
  return points;
}

/// What a text file that is not an 'x y' profile looks like, from its first line that says
/// something; "" when it may be one.
std::string looks_like(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (int lines = 0; lines < 50 && std::getline(in, line); ++lines) {
    const std::string content = trimmed(line.substr(0, line.find('#')));
    if (content.empty()) continue;
    const std::string head = upper(content.substr(0, 9));
    if (head.rfind("$CT", 0) == 0 || head.rfind("$ROAD_CRG", 0) == 0)
      return "an OpenCRG file: give it the extension .crg";
    if (content.front() == '[' || content.front() == '$' || content.front() == '!')
      return "a road data file (TeimOrbit sections): give it the extension .rdf";
    const bool separated = content.find_first_of(",;\t") != std::string::npos;
    const bool named = std::any_of(content.begin(), content.end(), [](char c) {
      return std::isalpha(static_cast<unsigned char>(c)) && c != 'e' && c != 'E';
    });
    if (separated && named) return "a CSV file with a header: give it the extension .csv";
    return "";
  }
  return "";
}

bool has_extension(const std::string& path, const char* extension) {
  const size_t dot = path.find_last_of('.');
  return dot != std::string::npos && path.find('/', dot) == std::string::npos && lower(path.substr(dot)) == extension;
}

}  // namespace

std::vector<Eigen::Vector2d> read_opencrg(const std::string& path, double v) { return OpenCrgFile(path).track(v); }

std::vector<Eigen::Vector2d> read_road_profile(const std::string& path, std::optional<RoadTrack> track,
                                               std::optional<double> v) {
  const bool csv = has_extension(path, ".csv"), crg = has_extension(path, ".crg");
  if (track && !csv)
    throw ModelError("'track' picks the track of a file with two (.csv, .rdf); '" + path + "' has one" +
                     (crg ? " track at each lateral position: give 'lateral' = v" : ""));
  if (v && !crg) throw ModelError("'lateral' picks the track of an OpenCRG file (.crg); '" + path + "' is not one");
  if (csv) return read_road_csv(path, track);
  if (crg) return read_opencrg(path, v.value_or(0.0));
  const std::string kind = looks_like(path);
  if (!kind.empty()) throw ModelError(path + ": not two columns 'x y': the file looks like " + kind);
  return RoadProfile::read_points(path);
}

}  // namespace tirefe
