// The contact macros: rigid surfaces (flat road, drum with a cleat, road profile) with
// their prescribed motion, node-to-surface contact blocks with friction, and queries of
// the contact results (docs/contact.md).
//
// Surfaces are kept by name in their DeckModel, so they die with the model; contact
// blocks hold their surface themselves.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "contact/node_contact.hpp"
#include "contact/tread_contact.hpp"
#include "formats/road_file.hpp"
#include "deck/contact_output.hpp"
#include "deck/deck_model.hpp"
#include "macros/macro_table.hpp"
#include "tire/contact_penalty.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

Eigen::Vector2d pair_of(const MacroArguments& arguments, const std::string& key, const Eigen::Vector2d& fallback) {
  if (!arguments.has(key)) return fallback;
  const std::vector<double> values = arguments.number_list(key);
  if (values.size() != 2) throw ModelError("'" + key + "' takes two numbers {x, y}");
  return {values[0], values[1]};
}

std::vector<double> triple_of(const MacroArguments& arguments, const std::string& key, const char* names) {
  const std::vector<double> values = arguments.number_list(key);
  if (values.size() != 3) throw ModelError("'" + key + "' takes three numbers {" + names + "}");
  return values;
}

/// The surface's motion along x (flat, profile) or its angle (drum).
MotionFunction motion_of(DeckModel& deck, const MacroArguments& arguments) {
  const bool by_speed = arguments.has("speed"), by_function = arguments.has("load_function");
  if (by_speed && by_function) throw ModelError("give either 'speed' or 'load_function', not both");
  auto refuse = [&](std::initializer_list<const char*> keys, const char* needs) {
    for (const char* key : keys)
      if (arguments.has(key)) throw ModelError(std::string("'") + key + "' needs '" + needs + "'");
  };
  if (!by_speed) refuse({"ramp_time", "start_time", "ramp"}, "speed");
  if (!by_function) refuse({"amplitude"}, "load_function");
  if (by_function)
    return MotionFunction::from_load_function(
        deck.model().load_function(deck.load_function(arguments.string("load_function"))),
        arguments.number("amplitude"));
  if (by_speed)
    return MotionFunction::ramped_rate(arguments.number("speed"), arguments.number("ramp_time"),
                                       arguments.number("start_time"), ramp_law_named(arguments.string("ramp")));
  return MotionFunction();
}

const ParameterSpec kRampKey{"ramp",
                             VT::String,
                             false,
                             "",
                             "how the rate rises over ramp_time: linear, or cosine, as (1 - cos) / 2 (no jerk at "
                             "either end)",
                             std::string("linear"),
                             Range::Any,
                             {"linear", "cosine"}};

int spin_up_macro(lua_State* L, DeckSession&, const MacroArguments& arguments) {
  const MotionFunction motion =
      MotionFunction::ramped_rate(arguments.number("rate"), arguments.number("ramp_time"),
                                  arguments.number("start_time"), ramp_law_named(arguments.string("ramp")));
  const double time = arguments.number("time");
  lua_pushnumber(L, motion.value(time));
  lua_pushnumber(L, motion.rate(time));
  return 2;
}

bool has_extension(const std::string& file, const std::string& extension) {
  std::string found = std::filesystem::path(file).extension().string();
  for (char& c : found) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return found == extension;
}

const char* surface_type(RoadShape::Kind kind) {
  return kind == RoadShape::Kind::Flat ? "flat" : kind == RoadShape::Kind::Drum ? "drum" : "profile";
}

std::optional<RoadTrack> track_of(const MacroArguments& arguments) {
  if (!arguments.has("track")) return std::nullopt;
  return arguments.string("track") == "left" ? RoadTrack::Left : RoadTrack::Right;
}

/// A profile's points from its file (src/formats/road_file.hpp), placed on the road by
/// 'start' (along x) and 'offset' (up).
std::vector<Eigen::Vector2d> file_profile(const std::string& file, const std::optional<RoadShape>& road,
                                          const MacroArguments& arguments) {
  if (road && arguments.has("lateral"))
    throw ModelError("'lateral' picks the track of an OpenCRG file (.crg); '" + file + "' is a road data file");
  std::vector<Eigen::Vector2d> points =
      road ? road->points
           : read_road_profile(
                 file, track_of(arguments),
                 arguments.has("lateral") ? std::optional<double>(arguments.number("lateral")) : std::nullopt);
  const Eigen::Vector2d shift(arguments.number("start"), arguments.number("offset"));
  for (Eigen::Vector2d& point : points) point += shift;
  return points;
}

/// The keys a surface type takes besides its name, type and motion; every other key of
/// model:surface is refused for it.
struct SurfaceKeys {
  const char* type;
  std::vector<std::string> own;
  std::vector<std::string> with_road_file;  // only with a road data file (.rdf)
  std::vector<std::string> from_road_file;  // given by a road data file: left out then
};

/// Keys every type takes: the surface's name and type, and its motion.
const std::vector<std::string> kEverySurfaceKeys{"name", "type",       "speed",         "ramp_time",
                                                 "ramp", "start_time", "load_function", "amplitude"};

bool listed(const std::vector<std::string>& keys, const std::string& key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

void refuse_given_by_file(const MacroArguments& arguments, const std::vector<std::string>& keys,
                          const std::string& file) {
  for (const std::string& key : keys)
    if (arguments.has(key)) throw ModelError("'" + key + "' is given by the file '" + file + "'; leave it out");
}

/// Refuses the keys 'keys' does not take; with a road data file, also those it gives.
void check_surface_keys(const MacroArguments& arguments, const SurfaceKeys& keys, const std::optional<RoadShape>& road,
                        const std::string& file) {
  for (const ParameterSpec& parameter : arguments.spec().parameters) {
    const std::string& key = parameter.key;
    if (!arguments.has(key) || listed(kEverySurfaceKeys, key) || listed(keys.own, key) ||
        (road && listed(keys.with_road_file, key)))
      continue;
    throw ModelError("'" + key + "' does not apply to a " + keys.type + " surface");
  }
  if (road) refuse_given_by_file(arguments, keys.from_road_file, file);
}

std::shared_ptr<const RigidSurface> build_flat(const MacroArguments& arguments, const std::optional<RoadShape>& road,
                                               const std::string& file, const MotionFunction& motion) {
  static const SurfaceKeys keys{"flat", {"point", "direction"}, {"file", "offset", "track"}, {"point", "direction"}};
  check_surface_keys(arguments, keys, road, file);
  const Eigen::Vector2d point =
      road ? Eigen::Vector2d(0.0, road->level + arguments.number("offset")) : pair_of(arguments, "point", {0, 0});
  return std::make_shared<FlatRoad>(point, pair_of(arguments, "direction", Eigen::Vector2d::UnitX()),
                                    RigidMotion::translation(motion));
}

std::shared_ptr<const RigidSurface> build_drum(const MacroArguments& arguments, const std::optional<RoadShape>& road,
                                               const std::string& file, const MotionFunction& motion) {
  static const SurfaceKeys keys{"drum",
                                {"diameter", "centre", "cleat_height", "cleat_length", "cleat_angle", "edge_radius"},
                                {"file", "track"},
                                {"diameter", "cleat_height", "cleat_length", "cleat_angle"}};
  check_surface_keys(arguments, keys, road, file);
  const double edge_radius = arguments.number("edge_radius");
  Cleat cleat;
  double diameter = 0.0;
  if (road) {
    if (road->cleat.edge_radius > 0.0) refuse_given_by_file(arguments, {"edge_radius"}, file);
    diameter = road->diameter;
    cleat = road->cleat;
    if (cleat.edge_radius == 0.0) cleat.edge_radius = edge_radius;
  } else {
    if (!arguments.has("diameter")) throw ModelError("a drum needs 'diameter'");
    diameter = arguments.number("diameter");
    cleat.height = arguments.number("cleat_height");
    cleat.arc_length = arguments.number("cleat_length");
    cleat.angle = arguments.number("cleat_angle");
    cleat.edge_radius = edge_radius;
  }
  if ((cleat.height > 0.0) != (cleat.arc_length > 0.0))
    throw ModelError("a cleat needs both 'cleat_height' and 'cleat_length'");
  return std::make_shared<Drum>(diameter, pair_of(arguments, "centre", Eigen::Vector2d::Zero()), motion, cleat);
}

std::shared_ptr<const RigidSurface> build_profile(const MacroArguments& arguments, const std::optional<RoadShape>& road,
                                                  const std::string& file, const MotionFunction& motion) {
  static const SurfaceKeys keys{
      "profile",
      {"file", "start", "offset", "track", "lateral", "points", "pothole", "cleat", "level", "edge_radius"},
      {},
      {}};
  check_surface_keys(arguments, keys, road, file);
  const int sources =
      arguments.has("file") + arguments.has("points") + arguments.has("pothole") + arguments.has("cleat");
  if (sources != 1) throw ModelError("a profile needs exactly one of 'file', 'points', 'pothole' or 'cleat'");
  if (arguments.has("level") && !arguments.has("pothole") && !arguments.has("cleat"))
    throw ModelError("'level' is the road around a 'pothole' or 'cleat' (a file's road is raised by 'offset')");
  const double level = arguments.number("level");
  std::vector<Eigen::Vector2d> points;
  if (arguments.has("file")) {
    points = file_profile(file, road, arguments);
  } else if (arguments.has("points")) {
    for (const auto& row : arguments.number_matrix("points")) {
      if (row.size() != 2) throw ModelError("each profile point is {x, y}");
      points.emplace_back(row[0], row[1]);
    }
  } else if (arguments.has("pothole")) {
    const auto p = triple_of(arguments, "pothole", "start, length, depth");
    points = RoadProfile::pothole_points(p[0], p[1], p[2], level);
  } else {
    const auto c = triple_of(arguments, "cleat", "start, length, height");
    points = RoadProfile::cleat_points(c[0], c[1], c[2], level);
  }
  return std::make_shared<RoadProfile>(points, arguments.number("edge_radius"), RigidMotion::translation(motion));
}

std::shared_ptr<const RigidSurface> build_surface(DeckModel& deck, const MacroArguments& arguments) {
  // A road data file names its own type.
  const std::string file = arguments.has("file") ? deck_relative(deck.session(), arguments.string("file")) : "";
  std::optional<RoadShape> road;
  if (has_extension(file, ".rdf")) road = read_road_data_file(file, track_of(arguments));
  if (!arguments.has("type") && !road)
    throw ModelError("give 'type' (flat, drum or profile), or a road data file (.rdf) as 'file'");
  const std::string type = arguments.has("type") ? arguments.string("type") : surface_type(road->kind);
  if (road && type != surface_type(road->kind))
    throw ModelError("type '" + type + "', but '" + file + "' holds a " + road->road_type + " road (type '" +
                     surface_type(road->kind) + "')");
  const MotionFunction motion = motion_of(deck, arguments);
  if (!arguments.has("file")) {
    for (const char* key : {"start", "offset", "track", "lateral"})
      if (arguments.has(key)) throw ModelError(std::string("'") + key + "' places a road read from a 'file'");
  }
  if (type == "flat") return build_flat(arguments, road, file, motion);
  if (type == "drum") return build_drum(arguments, road, file, motion);
  return build_profile(arguments, road, file, motion);
}

int surface_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const std::string name = arguments.string("name");
  io::require_path_name(name, "surface name");
  if (deck.has_surface(name)) throw ModelError("surface '" + name + "' is already defined");
  const std::shared_ptr<const RigidSurface> surface = build_surface(deck, arguments);
  deck.define_surface(name, surface);
  deck.describe_output([name, surface](io::ResultFile& file) { add_surface_output(file, name, surface); });
  return 0;
}

/// 'name', refused if it is not a plain name or an element block has it already.
std::string unused_block_name(DeckModel& deck, const std::string& name) {
  io::require_path_name(name, "contact block name");
  for (const auto& block : deck.model().blocks())
    if (block->name() == name) throw ModelError("an element block named '" + name + "' exists already (give 'name')");
  return name;
}

/// The history channels and per-point rows a contact macro asks for.
void add_output(DeckModel& deck, const MacroArguments& arguments, const ContactSource& source) {
  const std::string prefix = arguments.string_or("history", "");
  const int every = static_cast<int>(arguments.integer("output_every"));
  if (!prefix.empty() || every > 0)
    add_contact_output(deck.output_or_default(), deck.analysis(), source, prefix, every);
}

// Scaling the tangential penalty from the structure solves for unit loads at every contact
// node, one dense column of all the model's DOFs each: 256 MiB of them are some 2300 tire
// wedges, solved in seconds (8000 wedges would take 3 GB and minutes).
constexpr double kMaxUnitLoadBytes = 256.0 * 1024 * 1024;

/// The structure's tangential penalty for 'nodes', refused before the memory goes when its
/// unit loads would be dense columns beyond kMaxUnitLoadBytes.
double scaled_tangential_penalty(DeckModel& deck, const std::vector<int>& nodes, const RigidSurface& surface,
                                 double factor) {
  const double dofs = deck.model().mesh().dof_count();
  const double bytes = dofs * 2.0 * static_cast<double>(nodes.size()) * sizeof(double);
  if (bytes > kMaxUnitLoadBytes)
    throw ModelError("contact: scaling the tangential penalty from the structure at " + std::to_string(nodes.size()) +
                     " nodes of a model of " + std::to_string(static_cast<long long>(dofs)) + " DOFs would take " +
                     std::to_string(static_cast<long long>(bytes / (1024 * 1024))) +
                     " MiB of unit loads, more than the 256 MiB allowed; give tangential_penalty");
  return structural_tangential_penalty(deck.analysis(), nodes, surface, factor);
}

int contact_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const std::string surface_name = arguments.string("surface");
  const std::shared_ptr<const RigidSurface> surface = deck.surface(surface_name);
  const std::vector<int> nodes = target_nodes(deck, arguments);
  const std::string name = unused_block_name(deck, arguments.string_or("name", "contact_" + surface_name));
  ContactParameters parameters;
  parameters.friction = arguments.number("friction");
  if (!arguments.has("penalty") || !arguments.has("tangential_penalty"))
    deck.require_state("a default contact penalty (from the structure's stiffness)");
  parameters.normal_penalty = arguments.has("penalty")
                                  ? arguments.number("penalty")
                                  : structural_penalty(deck.analysis(), nodes, arguments.number("penalty_factor"));
  parameters.tangential_penalty =
      arguments.has("tangential_penalty")
          ? arguments.number("tangential_penalty")
          : scaled_tangential_penalty(deck, nodes, *surface, arguments.number("tangential_factor"));
  parameters.penetration_tolerance = arguments.number("tolerance");
  parameters.multiplier_tolerance = arguments.number("multiplier_tolerance");
  parameters.penetration_limit = arguments.number("penetration_limit");
  parameters.search_distance = arguments.number("search_distance");
  parameters.hold_first_evaluation = arguments.boolean("hold_first_evaluation");
  const ContactBlock& block =
      add_contact_block(deck.model(), name, surface, nodes, parameters, deck.analysis().state().time);
  add_output(deck, arguments, contact_source(block));
  lua_pushnumber(L, parameters.normal_penalty);
  lua_pushnumber(L, parameters.tangential_penalty);
  return 2;
}

int tire_contact_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const std::string surface_name = arguments.string("surface");
  const std::shared_ptr<const RigidSurface> surface = deck.surface(surface_name);
  const Tire& tire = deck.tire(arguments.string("tire"));
  const std::string name = unused_block_name(deck, arguments.string_or("name", "contact_" + surface_name));
  TreadRubber rubber = tread_rubber(tire.parameters, arguments.number("friction"));
  rubber.search_distance = arguments.number("search_distance");
  const TreadContactBlock& block = add_tread_contact_block(deck.model(), name, surface, tire.tread_nodes, rubber);
  add_output(deck, arguments, contact_source(block));
  lua_pushstring(L, name.c_str());
  return 1;
}

const std::vector<std::string> kQuantities{
    "fx", "fy", "patch_length", "nodes_in_contact", "nodes_slipping", "max_penetration"};

int contact_value_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const std::string name = arguments.string("name");
  const ElementBlock& any = deck.model().block(name);
  ContactSummary summary;
  if (const auto* nodes = dynamic_cast<const ContactBlock*>(&any))
    summary = summarize_contact(*nodes);
  else if (const auto* tread = dynamic_cast<const TreadContactBlock*>(&any))
    summary = summarize_contact(*tread);
  else
    throw ModelError("block '" + name + "' is not a contact block");
  const std::string quantity = arguments.string("quantity");
  const double values[] = {summary.force.x(),
                           summary.force.y(),
                           summary.patch_length,
                           static_cast<double>(summary.nodes_in_contact),
                           static_cast<double>(summary.nodes_slipping),
                           summary.max_penetration};
  for (size_t i = 0; i < kQuantities.size(); ++i)
    if (kQuantities[i] == quantity) lua_pushnumber(L, values[i]);
  return 1;
}

int surface_projection_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const std::shared_ptr<const RigidSurface> surface = deck.surface(arguments.string("surface"));
  const Eigen::Vector2d point = pair_of(arguments, "point", Eigen::Vector2d::Zero());
  const SurfaceProjection projection =
      surface->project(point, arguments.number_or("time", deck.analysis().state().time));
  lua_createtable(L, 0, 5);
  for (const auto& [name, value] : {std::pair<const char*, double>{"gap", projection.gap},
                                    {"x", projection.point.x()},
                                    {"y", projection.point.y()},
                                    {"coordinate", projection.coordinate}}) {
    lua_pushnumber(L, value);
    lua_setfield(L, -2, name);
  }
  lua_createtable(L, 2, 0);
  for (int i = 0; i < 2; ++i) {
    lua_pushnumber(L, projection.normal[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "normal");
  return 1;
}

}  // namespace

void add_contact_macros(MacroTable& table) {
  table.module_macros.push_back(
      {{"spin_up",
        "The value and the rate at 'time' of a motion whose rate rises from rest at 'start_time' to 'rate' over "
        "'ramp_time' (the drum surface's motion by 'speed', 'ramp_time', 'ramp' and 'start_time'): what "
        "lua/drum.lua plans a drum's turn with. Returns the value (the angle for a spin) and the rate.",
        {{"rate", VT::Number, true, "rad/s or m/s", "the final rate of an angle or a travel"},
         {"ramp_time", VT::Number, true, "s", "time to reach 'rate' from rest", std::nullopt, Range::NonNegative},
         kRampKey,
         {"start_time", VT::Number, false, "s", "when the ramp starts", std::string("0")},
         {"time", VT::Number, true, "s", "when the value and rate are read"}},
        "local angle, spin = tirefe.spin_up{ rate = 16.76, ramp_time = 4.0, start_time = 2.0, time = 3.0 }"},
       spin_up_macro});
  auto add = [&table](MacroSpec spec, ModelHandler handler) {
    table.model_macros.push_back({std::move(spec), handler});
  };
  add({"surface",
       "Defines a named rigid surface for contact (docs/contact.md): a flat road, a drum (optionally with a cleat) "
       "or a road profile (points, a file, a pothole or a cleat on a level road). A road file is a two-column "
       "'x y' text, a CSV file with a header (x_m, z_mm, ...), an ASCII OpenCRG file (.crg) or an ADAMS road data "
       "file (.rdf: flat, poly_line, plank, pot_hole or drum, which sets the type); 'start' and 'offset' place it, "
       "'track' picks the left or right track of a file with two, 'lateral' the track of an OpenCRG file. The solid lies on the right when walking along the surface (below a "
       "road, inside a drum). Roads and profiles translate along x, drums turn about their centre: by 'speed' "
       "(ramped from rest over 'ramp_time' from 'start_time') or by 'amplitude' times a load function.",
       {{"name", VT::String, true, "", "surface name"},
        {"type",
         VT::String,
         false,
         "",
         "kind of surface (required unless 'file' is a road data file)",
         std::nullopt,
         Range::Any,
         {"flat", "drum", "profile"}},
        {"point", VT::NumberList, false, "m", "flat: a point of the road {x, y}", std::string("{0, 0}")},
        {"direction", VT::NumberList, false, "", "flat: direction along the road {dx, dy}", std::string("{1, 0}")},
        {"diameter", VT::Number, false, "m", "drum: diameter", std::nullopt, Range::Positive},
        {"centre", VT::NumberList, false, "m", "drum: centre {x, y}", std::string("{0, 0}")},
        {"cleat_height", VT::Number, false, "m", "drum: radial height of the cleat (0: none)", std::string("0"),
         Range::NonNegative},
        {"cleat_length", VT::Number, false, "m", "drum: length of the cleat along the drum surface", std::string("0"),
         Range::NonNegative},
        {"cleat_angle", VT::Number, false, "rad", "drum: angular position of the cleat's middle at rest, from +x",
         std::string("1.5707963267948966")},
        {"file", VT::String, false, "",
         "profile: two-column text file 'x y' ('#' comments), CSV file (.csv) with a header or ASCII OpenCRG file "
         "(.crg); any type: a road data file (.rdf); relative to the deck's folder"},
        {"start", VT::Number, false, "m", "file: where the file's x = 0 lies along the road", std::string("0")},
        {"offset", VT::Number, false, "m", "file: height added to the file's road", std::string("0")},
        {"track",
         VT::String,
         false,
         "",
         "file: the track of a file with a left and a right one",
         std::nullopt,
         Range::Any,
         {"left", "right"}},
        {"lateral", VT::Number, false, "m",
         "OpenCRG file: the lateral position v of the track, left of the reference line positive (default 0: the "
         "reference line)"},
        {"points", VT::NumberMatrix, false, "m", "profile: {x, y} points, x not decreasing"},
        {"pothole", VT::NumberList, false, "m", "profile: a pothole {start, length, depth} in a level road"},
        {"cleat", VT::NumberList, false, "m", "profile: a cleat {start, length, height} on a level road"},
        {"level", VT::Number, false, "m", "profile: road height around a pothole or cleat", std::string("0")},
        {"edge_radius", VT::Number, false, "m", "drum, profile: rounding radius of the convex edges", std::string("0"),
         Range::NonNegative},
        {"speed", VT::Number, false, "m/s or rad/s", "final speed along x (flat, profile) or spin (drum, ccw)"},
        {"ramp_time", VT::Number, false, "s", "time to reach 'speed' from rest", std::string("0"), Range::NonNegative},
        kRampKey,
        {"start_time", VT::Number, false, "s", "when the ramp starts", std::string("0")},
        {"load_function", VT::String, false, "", "x offset (flat, profile) or angle (drum) = amplitude * f(t)"},
        {"amplitude", VT::Number, false, "m or rad", "scale of the load function", std::string("1")}},
       "model:surface{ name = \"drum\", type = \"drum\", diameter = 1.7, cleat_height = 0.025, cleat_length = 0.66,\n"
       "               edge_radius = 0.005, speed = 16.8, ramp_time = 4.0, start_time = 2.0 }"},
      surface_macro);
  add({"contact",
       "Node-to-surface contact with Coulomb friction by the augmented Lagrangian method, one element per node. "
       "Without 'penalty' the normal penalty is penalty_factor times the largest diagonal stiffness of the "
       "structure at the nodes; without 'tangential_penalty' the tangential one is tangential_factor times the "
       "smallest stiffness of the structure along the surface at the nodes (define and support the structure "
       "first). Returns the normal and tangential penalties used.",
       {{"surface", VT::String, true, "", "surface name"},
        node_key(),
        set_key(),
        {"name", VT::String, false, "", "element block name", std::string("contact_<surface>")},
        {"friction", VT::Number, false, "", "Coulomb coefficient mu", std::string("0"), Range::NonNegative},
        {"penalty", VT::Number, false, "N/m", "normal penalty eps_N", std::nullopt, Range::Positive},
        {"penalty_factor", VT::Number, false, "", "eps_N / largest diagonal stiffness at the nodes", std::string("1"),
         Range::Positive},
        {"tangential_penalty", VT::Number, false, "N/m", "tangential penalty eps_T", std::nullopt, Range::Positive},
        {"tangential_factor", VT::Number, false, "",
         "eps_T / smallest tangential stiffness of the structure itself at the nodes", std::string("1"),
         Range::Positive},
        {"tolerance", VT::Number, false, "m", "penetration allowed after the Uzawa updates", std::string("5e-4"),
         Range::NonNegative},
        {"multiplier_tolerance", VT::Number, false, "", "relative multiplier change allowed", std::string("0.01"),
         Range::NonNegative},
        {"penetration_limit", VT::Number, false, "m", "deeper penetration fails the step", std::string("0.01"),
         Range::Positive},
        {"search_distance", VT::Number, false, "m",
         "open nodes farther from the surface than this skip the projection (more than a step's approach)",
         std::string("0.05"), Range::Positive},
        {"hold_first_evaluation", VT::Boolean, false, "",
         "a solve's first evaluation keeps the nodes in contact that were when the step began, lifted off by the "
         "predictor or not (for light patch nodes whose predicted rates alternate)",
         std::string("false")},
        {"history", VT::String, false, "",
         "prefix of history channels <prefix>_fx, _fy, _patch_length, "
         "_nodes_in_contact, _surface_angle, _surface_x"},
        {"output_every", VT::Integer, false, "", "write per-node rows (/contact/<name>/...) every n steps; 0: never",
         std::string("0"), Range::NonNegative}},
       "model:contact{ surface = \"drum\", set = \"tread\", friction = 0.3, history = \"patch\" }"},
      contact_macro);
  add({"tire_contact",
       "A tire's tread against a surface through its tread rubber (docs/contact.md, Tread contact): a massless "
       "layer whose radial and shear stiffness and damping (the tire's tread_layer_* parameters) make a compliant "
       "contact law with Coulomb friction, sampled along every chord of the tread. Returns the block's name.",
       {{"surface", VT::String, true, "", "surface name"},
        {"tire", VT::String, false, "", "the tire's name (model:tire{ name })", std::string("tire")},
        {"name", VT::String, false, "", "element block name", std::string("contact_<surface>")},
        {"friction", VT::Number, false, "", "Coulomb coefficient mu", std::string("0"), Range::NonNegative},
        {"search_distance", VT::Number, false, "m",
         "sample points open when their step began and farther from the surface than this are not projected",
         std::string("0.005"), Range::Positive},
        {"history", VT::String, false, "",
         "prefix of history channels <prefix>_fx, _fy, _patch_length, _nodes_in_contact (sample points), "
         "_surface_angle, _surface_x"},
        {"output_every", VT::Integer, false, "", "write per-sample rows (/contact/<name>/...) every n steps; 0: never",
         std::string("0"), Range::NonNegative}},
       "model:tire_contact{ surface = \"drum\", friction = 0.3, history = \"drum\" }"},
      tire_contact_macro);
  add({"contact_value",
       "Returns a total of a contact block at the current time: force on the structure (fx, fy), patch length, "
       "nodes in contact or slipping, or the largest penetration.",
       {{"name", VT::String, true, "", "contact block name (contact_<surface> by default)"},
        {"quantity", VT::String, true, "", "what to return", std::nullopt, Range::Any, kQuantities}},
       "local fy = model:contact_value{ name = \"contact_drum\", quantity = \"fy\" }"},
      contact_value_macro);
  add({"surface_projection",
       "Projects a point onto a surface (docs/contact.md, as the contact does): returns {gap (negative inside "
       "the solid), x, y (the closest point), normal = {nx, ny} (outward), coordinate (arc length s)}, for decks "
       "that check a surface's geometry.",
       {{"surface", VT::String, true, "", "surface name"},
        {"point", VT::NumberList, true, "m", "the point {x, y}"},
        {"time", VT::Number, false, "s", "time of the surface's motion (default: the model's time)"}},
       "local p = model:surface_projection{ surface = \"road\", point = { 1.2, 0.1 } }\nprint(p.gap, p.y)"},
      surface_projection_macro);
}

}  // namespace tirefe::macros
