// Tire property files (.tir, TeimOrbit format: src/formats/teim_orbit.hpp): tirefe.read_tire{...}
// returns the model:tire parameter table a file holds, tirefe.write_tire{...} writes one
// (docs/tire.md). A file of tirefe's own ring ([MODEL] PROPERTY_FILE_FORMAT = 'TIREFE') is
// read through the table below, the whole mapping: each file key, the dimension its value
// is converted by, and the model:tire key it becomes; ranges, defaults and meanings are
// those of model:tire's own spec. Any other file is a standard (Magic Formula) one, read by
// src/formats/mf_tire_file.hpp into a ring of its size, with what it states beside it.
#include <cmath>

#include "formats/mf_tire_file.hpp"
#include "formats/teim_orbit.hpp"
#include "deck/deck_session.hpp"
#include "macros/macro_table.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;
using formats::Dimension;

constexpr const char* kFormat = "TIREFE";  // [MODEL] PROPERTY_FILE_FORMAT of tirefe's ring tire

struct TireFileKey {
  const char* section;
  const char* key;
  Dimension dimension;
  const char* parameter;    // the model:tire key
  double file_scale = 1.0;  // file value = file_scale * parameter (0.5: a radius for a diameter)
};

constexpr Dimension kLength{1};
constexpr Dimension kForce{0, 1};
constexpr Dimension kMass{0, 0, 1};
constexpr Dimension kPerLength2Force{-2, 1};   // N/m^2
constexpr Dimension kDamping{-2, 1, 0, 1};     // N s/m^2
constexpr Dimension kMassPerLength{-1, 0, 1};  // kg/m

// In file order. [DIMENSION] UNLOADED_RADIUS and RIM_RADIUS and [OPERATING_CONDITIONS]
// INFLPRES are the standard names of MF-Tyre files; the other sections are tirefe's own.
const TireFileKey kTireFileKeys[] = {
    {"MODEL", "ELEMENTS", {}, "elements"},
    {"DIMENSION", "UNLOADED_RADIUS", kLength, "outer_diameter", 0.5},
    {"DIMENSION", "RIM_RADIUS", kLength, "rim_diameter", 0.5},
    {"OPERATING_CONDITIONS", "INFLPRES", Dimension{0, 0, 0, 0, 0, 1}, "pressure"},
    {"TREAD", "WIDTH", kLength, "tread_width"},
    {"TREAD", "AXIAL_STIFFNESS", kForce, "tread_EA"},
    {"TREAD", "SHEAR_STIFFNESS", kForce, "tread_GA"},
    {"TREAD", "BENDING_STIFFNESS", Dimension{2, 1}, "tread_EI"},
    {"TREAD", "MASS_PER_LENGTH", kMassPerLength, "tread_mass_per_length"},
    {"TREAD", "ROTARY_INERTIA_PER_LENGTH", Dimension{1, 0, 1}, "tread_rotary_inertia_per_length"},
    {"TREAD", "CURVATURE_DAMPING", Dimension{2, 1, 0, 1}, "tread_curvature_damping"},
    {"SIDEWALL", "LENGTH", kLength, "sidewall_length"},
    {"SIDEWALL", "BENDING_STIFFNESS", Dimension{1, 1}, "k_sw"},
    {"SIDEWALL", "BENDING_SIGN", {}, "k_sw_sign"},
    {"SIDEWALL", "SHEAR_STIFFNESS", Dimension{-1, 1, 0, 0, -1}, "k_gamma"},
    {"SIDEWALL", "RADIAL_DAMPING", kDamping, "sidewall_radial_damping"},
    {"SIDEWALL", "CIRCUMFERENTIAL_DAMPING", kDamping, "sidewall_circumferential_damping"},
    {"TREAD_LAYER", "RADIAL_STIFFNESS", kPerLength2Force, "tread_layer_radial_stiffness"},
    {"TREAD_LAYER", "CIRCUMFERENTIAL_STIFFNESS", kPerLength2Force, "tread_layer_circumferential_stiffness"},
    {"TREAD_LAYER", "MASS_PER_LENGTH", kMassPerLength, "tread_layer_mass_per_length"},
    {"TREAD_LAYER", "RADIAL_DAMPING", kDamping, "tread_layer_radial_damping"},
    {"TREAD_LAYER", "CIRCUMFERENTIAL_DAMPING", kDamping, "tread_layer_circumferential_damping"},
    {"RIM", "MASS", kMass, "rim_mass"},
    {"RIM", "ROTARY_INERTIA", Dimension{2, 0, 1}, "rim_rotary_inertia"},
};

/// The model:tire keys that place a tire in a model rather than describe it.
const char* const kPlacementKeys[] = {"name", "pressure_load_function", "x", "y"};

const ParameterSpec& tire_parameter(const std::string& key) {
  for (const ParameterSpec& parameter : model_macro_spec("tire").parameters)
    if (parameter.key == key) return parameter;
  throw std::logic_error("model:tire has no key '" + key + "'");
}

std::string file_key(const TireFileKey& key) { return std::string("[") + key.section + "] " + key.key; }

/// A standard file's parameter table, checked by model:tire's ranges as the own format's is.
void push_ring_parameters(lua_State* L, const formats::TeimOrbitReader& reader,
                          const std::vector<RingParameter>& ring) {
  lua_createtable(L, 0, static_cast<int>(ring.size()));
  for (const RingParameter& parameter : ring) {
    const ParameterSpec& spec = tire_parameter(parameter.key);
    if (!std::isfinite(parameter.value))
      reader.fail(0, parameter.key + " (" + parameter.origin + ") is not finite: the file's sizes are out of scale");
    if (const auto problem = range_problem(spec, parameter.value))
      reader.fail(0, parameter.key + " (" + parameter.origin + ") " + *problem);
    if (spec.type == VT::Integer)
      lua_pushinteger(L, static_cast<lua_Integer>(parameter.value));
    else
      lua_pushnumber(L, parameter.value);
    lua_setfield(L, -2, parameter.key.c_str());
  }
}

void set_number(lua_State* L, const char* key, const std::optional<double>& value) {
  if (!value) return;
  lua_pushnumber(L, *value);
  lua_setfield(L, -2, key);
}

/// What a standard file states, in SI (docs/tire.md, "Your tire from a standard file").
void push_stated(lua_State* L, const MfTireFile& tire, const std::vector<RingParameter>& ring) {
  double pressure = 0.0;
  for (const RingParameter& parameter : ring)
    if (parameter.key == "pressure") pressure = parameter.value;
  lua_newtable(L);
  lua_pushstring(L, tire.path.c_str());
  lua_setfield(L, -2, "file");
  lua_pushstring(L, tire.format.c_str());
  lua_setfield(L, -2, "format");
  lua_pushstring(L, tire.deflection_load.empty() ? "VERTICAL_STIFFNESS" : "DEFLECTION_LOAD_CURVE");
  lua_setfield(L, -2, "vertical_law");
  set_number(L, "pressure", pressure);
  set_number(L, "nominal_load", tire.nominal_load);
  if (tire.nominal_load) {
    const auto deflection = tire.stated_deflection(*tire.nominal_load, pressure);
    set_number(L, "nominal_deflection", deflection);
    if (deflection && *deflection > 0.0) {
      set_number(L, "vertical_stiffness", *tire.nominal_load / *deflection);
      set_number(L, "half_load", tire.stated_load(0.5 * *deflection, pressure));
    }
  }
  set_number(L, "longitudinal_stiffness", tire.longitudinal_stiffness);
  set_number(L, "longitudinal_frequency", tire.longitudinal_frequency);
  set_number(L, "windup_frequency", tire.windup_frequency);
  set_number(L, "longitudinal_damping", tire.longitudinal_damping);
  set_number(L, "windup_damping", tire.windup_damping);
  set_number(L, "mass", tire.mass);
  set_number(L, "polar_inertia", tire.polar_inertia);
  if (tire.belt_mass)
    set_number(L, "belt_mass", tire.belt_mass);
  else if (tire.pac2002_belt_mass && *tire.pac2002_belt_mass > 0.0)
    set_number(L, "belt_mass", tire.pac2002_belt_mass);
  set_number(L, "belt_polar_inertia", tire.belt_polar_inertia);
  lua_createtable(L, 0, static_cast<int>(ring.size()));
  for (const RingParameter& parameter : ring) {
    lua_pushstring(L, parameter.origin.c_str());
    lua_setfield(L, -2, parameter.key.c_str());
  }
  lua_setfield(L, -2, "origins");
}

/// Pushes the model:tire table of a file of tirefe's own ring.
void push_own_tire_file(lua_State* L, const formats::TeimOrbitFile& file, formats::TeimOrbitReader& reader);
/// Pushes the model:tire table of any tire property file, and with 'stated' what a standard
/// file states (nil for one of tirefe's own). Returns the number of values pushed.
int push_tire_file(lua_State* L, const std::string& path, std::optional<double> pressure,
                   std::optional<double> tread_width, bool stated);

int read_tire_macro(lua_State* L, DeckSession& session, const MacroArguments& arguments) {
  const auto optional_number = [&](const char* key) {
    return arguments.has(key) ? std::optional<double>(arguments.number(key)) : std::nullopt;
  };
  return push_tire_file(L, deck_relative(session, arguments.string("file")), optional_number("pressure"),
                        optional_number("tread_width"), true);
}

/// The parameter table validated as model:tire's, refusing the keys that are not properties.
const MacroSpec& written_parameters_spec() {
  static const MacroSpec spec = [] {
    MacroSpec copy = model_macro_spec("tire");
    copy.name = "write_tire parameters";
    return copy;
  }();
  return spec;
}

int write_tire_macro(lua_State* L, DeckSession& session, const MacroArguments& arguments) {
  arguments.push_value("parameters");
  const MacroArguments parameters(L, -1, written_parameters_spec());
  for (const char* key : kPlacementKeys)
    if (parameters.has(key))
      throw std::invalid_argument(std::string("'parameters' key '") + key +
                                  "' places a tire in a model; it is not a tire property (leave it out)");
  std::vector<std::string> comments;
  if (arguments.has("comments")) comments = arguments.string_list("comments");
  formats::TeimOrbitWriter writer("tir", comments);
  std::string section;
  for (const TireFileKey& key : kTireFileKeys) {
    if (key.section != section) {
      section = key.section;
      writer.section(section);
      if (section == "MODEL") writer.string("PROPERTY_FILE_FORMAT", kFormat, "tirefe's ring tire (docs/tire.md)");
    }
    const ParameterSpec& parameter = tire_parameter(key.parameter);
    const double value = parameter.type == VT::Integer ? static_cast<double>(parameters.integer(key.parameter))
                                                       : parameters.number(key.parameter);
    const std::string unit = formats::si_unit(key.dimension);
    const std::string meaning = key.file_scale != 1.0
                                    ? "half of " + std::string(key.parameter) + " (" + parameter.doc + ")"
                                    : std::string(key.parameter) + ": " + parameter.doc;
    writer.number(key.key, key.file_scale * value, meaning + (unit.empty() ? "" : " [" + unit + "]"));
  }
  lua_pop(L, 1);
  const std::string path = deck_output_path(
      session, arguments.string("file"), {"a tire property file (tirefe.write_tire)", "a tire property file", "$---"});
  if (session.processes.rank == 0) writer.save(path);  // every process runs the deck: one writes
  lua_pushstring(L, path.c_str());
  return 1;
}

}  // namespace

namespace {

int push_tire_file(lua_State* L, const std::string& path, std::optional<double> pressure,
                   std::optional<double> tread_width, bool stated) {
  const formats::TeimOrbitFile file = formats::TeimOrbitFile::read(path);
  formats::TeimOrbitReader reader(file, "tir");
  const auto format = reader.string("MODEL", "PROPERTY_FILE_FORMAT");
  if (!format || !formats::same_name(*format, kFormat)) {
    // tirefe's own sections in a file that does not name the format: a mix-up, not a standard file.
    for (const char* own : {"TREAD", "SIDEWALL", "TREAD_LAYER", "RIM"})
      if (file.section(own))
        reader.fail(format ? reader.line("MODEL", "PROPERTY_FILE_FORMAT") : file.section(own)->line,
                    (format ? "[MODEL] PROPERTY_FILE_FORMAT = '" + *format + "', but " : std::string()) + "[" + own +
                        "] is a section of tirefe's ring tire: name its format, [MODEL] PROPERTY_FILE_FORMAT = '" +
                        kFormat + "'");
    const MfTireFile tire = MfTireFile::read(file, reader);
    const std::vector<RingParameter> ring = ring_parameters(tire, pressure, tread_width);
    push_ring_parameters(L, reader, ring);
    if (!stated) return 1;
    push_stated(L, tire, ring);
    return 2;
  }
  if (tread_width)
    reader.fail(reader.line("MODEL", "PROPERTY_FILE_FORMAT"),
                "'tread_width' applies to a standard file; this one holds [TREAD] WIDTH itself");
  push_own_tire_file(L, file, reader);
  if (pressure) {
    lua_pushnumber(L, *pressure);
    lua_setfield(L, -2, "pressure");
  }
  return 1;
}

void push_own_tire_file(lua_State* L, const formats::TeimOrbitFile& file, formats::TeimOrbitReader& reader) {
  std::vector<std::optional<double>> values;
  for (const TireFileKey& key : kTireFileKeys) values.push_back(reader.number(key.section, key.key, key.dimension));
  // The standard file's other dimensions may stand beside the ring's: they describe the
  // size, [TREAD] WIDTH is the width the pressure acts on.
  for (const char* key : {"WIDTH", "ASPECT_RATIO", "RIM_WIDTH"}) reader.number("DIMENSION", key);
  reader.finish();  // a misspelt key is reported as such, not as a missing one

  lua_createtable(L, 0, static_cast<int>(values.size()));
  for (size_t i = 0; i < values.size(); ++i) {
    const TireFileKey& key = kTireFileKeys[i];
    const ParameterSpec& parameter = tire_parameter(key.parameter);
    if (!values[i]) {
      if (!parameter.required) continue;  // model:tire's default
      const formats::TeimOrbitSection* section = file.section(key.section);
      const std::string dimension =
          key.dimension.dimensionless() ? "" : ", a " + formats::dimension_name(key.dimension);
      reader.fail(section ? section->line : 0, "missing " + file_key(key) + " (" +
                                                   (key.file_scale != 1.0 ? "half of " : "") + key.parameter + ": " +
                                                   parameter.doc + dimension + ")");
    }
    const double value = *values[i] / key.file_scale;
    const int line = reader.line(key.section, key.key);
    if (const auto problem = range_problem(parameter, value))
      reader.fail(line, file_key(key) + ": " + key.parameter + " " + *problem);
    if (parameter.type == VT::Integer) {
      if (value != std::floor(value) || value > 1e9)
        reader.fail(
            line, file_key(key) + " must be a whole number below 1e9 (got " + formats::round_trip_number(value) + ")");
      lua_pushinteger(L, static_cast<lua_Integer>(value));
    } else {
      lua_pushnumber(L, value);
    }
    lua_setfield(L, -2, key.parameter);
  }
}

}  // namespace

int push_tire_property_file(lua_State* L, const std::string& path) {
  return push_tire_file(L, path, std::nullopt, std::nullopt, false);
}

std::string tire_property_file_reference() {
  std::string out = "| section | key | dimension | SI unit | model:tire key | meaning |\n|---|---|---|---|---|---|\n";
  for (const TireFileKey& key : kTireFileKeys) {
    const ParameterSpec& parameter = tire_parameter(key.parameter);
    const std::string need = parameter.required ? "required" : "default " + parameter.default_value.value_or("none");
    out += std::string("| `[") + key.section + "]` | `" + key.key + "` | " + formats::dimension_name(key.dimension) +
           " | " + formats::si_unit(key.dimension) + " | `" + key.parameter + "`" +
           (key.file_scale != 1.0 ? " / 2 (the file holds the radius)" : "") + " | " + parameter.doc + " (" + need +
           ") |\n";
  }
  return out;
}

void add_tire_file_macros(MacroTable& table) {
  table.module_macros.push_back(
      {{"read_tire",
        "Reads a tire property file (.tir, TeimOrbit format as ADAMS/Tire, MF-Tyre and FTire read; docs/tire.md "
        "lists every key) and returns its model:tire parameter table in SI, converted from the file's [UNITS]. "
        "A file of tirefe's ring ([MODEL] PROPERTY_FILE_FORMAT = 'TIREFE') holds the table itself: keys it "
        "leaves out take model:tire's defaults. Any other file is a standard MF-Tyre / MF-Swift (PAC2002, 5.2 "
        "to 6.2) file: the table is a ring of its size, pressure and masses, and a second value holds what the "
        "file states (vertical stiffness at FNOMIN, in-plane modes, the origin of each parameter), for "
        "lua/tire_identify.lua to fit the ring to. A malformed file, a missing or unknown unit, a repeated key "
        "tirefe reads or a value that is not a number stops the deck with the file, line and key.",
        {{"file", VT::String, true, "", "tire property file, relative to the deck's folder"},
         {"pressure", VT::Number, false, "Pa",
          "inflation pressure to build the tire at (default: the file's; required for a standard file that states "
          "none)",
          std::nullopt, Range::Positive},
         {"tread_width", VT::Number, false, "m",
          "standard file: the width the pressure acts on (default 3/4 of [DIMENSION] WIDTH; the sidewall's length "
          "follows it); lua/tire_identify.lua fits it",
          std::nullopt, Range::Positive}},
        "local tp = tirefe.read_tire{ file = \"tires/145SR12.tir\" }\ntp.pressure = 0.243e6\n"
        "local tire = model:tire(tp)"},
       read_tire_macro});
  table.module_macros.push_back(
      {{"write_tire",
        "Writes a model:tire parameter table as a tire property file (docs/tire.md), in SI units with every "
        "key; numbers are written so that read_tire gives back the same values bit for bit. Returns the path "
        "written.",
        {{"file", VT::String, true, "", "the .tir file to write (relative paths go in the output folder)"},
         {"parameters", VT::Table, true, "", "model:tire parameters (without name, pressure_load_function, x, y)"},
         {"comments", VT::StringList, false, "", "lines of the file's (COMMENTS) block"}},
        "tirefe.write_tire{ file = \"145SR12.tir\", parameters = require(\"tires.145SR12\"),\n"
        "                   comments = { \"145 SR-12, the paper's model\" } }"},
       write_tire_macro});
}

}  // namespace tirefe::macros
