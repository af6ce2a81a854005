// model:tire{...}: builds a ring tire from named physical parameters (src/tire/).
// Tire parameter sets live in lua/tires/*.lua: model:tire(require("tires.145SR12")), or in
// tire property files (tire_file_macros.cpp).
#include <cmath>

#include "deck/deck_files.hpp"
#include "deck/deck_model.hpp"
#include "macros/macro_table.hpp"
#include "tire/tire_builder.hpp"
#include "deck/lua_module_dir.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

// More wedges than this are no tire anyone solves (100 resolve the contact patch); a
// number like 2e7 is a typo, refused before the memory goes.
constexpr long long kMaxTireElements = 100000;

TireParameters tire_parameters(const MacroArguments& arguments) {
  TireParameters parameters;
  parameters.elements = static_cast<int>(arguments.integer("elements"));
  parameters.outer_diameter = arguments.number("outer_diameter");
  parameters.rim_diameter = arguments.number("rim_diameter");
  parameters.tread_width = arguments.number("tread_width");
  parameters.pressure = arguments.number("pressure");
  parameters.tread.axial_stiffness = arguments.number("tread_EA");
  parameters.tread.shear_stiffness = arguments.number("tread_GA");
  parameters.tread.bending_stiffness = arguments.number("tread_EI");
  parameters.tread.mass_per_length = arguments.number("tread_mass_per_length");
  parameters.tread.rotary_inertia_per_length = arguments.number("tread_rotary_inertia_per_length");
  parameters.tread.curvature_damping = arguments.number("tread_curvature_damping");
  parameters.sidewall.cord_length = arguments.number("sidewall_length");
  parameters.sidewall.bending_stiffness = arguments.number("k_sw");
  parameters.sidewall.bending_sign = arguments.number("k_sw_sign");
  parameters.sidewall.shear_stiffness = arguments.number("k_gamma");
  parameters.sidewall.radial_damping = arguments.number("sidewall_radial_damping");
  parameters.sidewall.circumferential_damping = arguments.number("sidewall_circumferential_damping");
  parameters.rim_mass = arguments.number("rim_mass");
  parameters.rim_rotary_inertia = arguments.number("rim_rotary_inertia");
  parameters.tread_layer.radial_stiffness = arguments.number("tread_layer_radial_stiffness");
  parameters.tread_layer.circumferential_stiffness = arguments.number("tread_layer_circumferential_stiffness");
  parameters.tread_layer.mass_per_length = arguments.number("tread_layer_mass_per_length");
  parameters.tread_layer.radial_damping = arguments.number("tread_layer_radial_damping");
  parameters.tread_layer.circumferential_damping = arguments.number("tread_layer_circumferential_damping");
  parameters.centre = {arguments.number("x"), arguments.number("y")};
  return parameters;
}

int tire_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const TireParameters parameters = tire_parameters(arguments);
  const std::string name = arguments.string("name");
  io::require_path_name(name, "tire name");  // its node sets are named after it
  const Tire tire =
      build_tire(deck.model(), parameters,
                 deck.model().load_function(deck.load_function(arguments.string("pressure_load_function"))), name);
  // Spindle equations last, as the spindle-force condensation and the RingSolver's border want them.
  deck.model().condense_node(tire.spindle);
  deck.analysis().prefer_ring_solver(tire.tread_nodes, {tire.spindle});
  deck.define_tire(tire);
  // The result file takes the rim's rigid motion out of the tire's nodes (/fields/deformation).
  Heading heading = Heading::PlusX;
  parse_heading(arguments.string("heading"), heading);  // the spec allows +x and -x only
  deck.set_wheel_heading(tire.spindle, heading);
  deck.describe_output([spindle = tire.spindle, carried = tire.tread_nodes, heading](io::ResultFile& file) {
    file.file().write_attribute("/", "heading", std::string(heading_name(heading)));
    file.add_rim(spindle, carried);
  });
  lua_createtable(L, 0, 5);
  lua_pushstring(L, name.c_str());
  lua_setfield(L, -2, "name");
  lua_pushinteger(L, tire.spindle + 1);
  lua_setfield(L, -2, "spindle");
  lua_createtable(L, static_cast<int>(tire.tread_nodes.size()), 0);
  for (size_t i = 0; i < tire.tread_nodes.size(); ++i) {
    lua_pushinteger(L, tire.tread_nodes[i] + 1);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "tread");
  lua_pushstring(L, (name + "_spindle").c_str());
  lua_setfield(L, -2, "spindle_set");
  lua_pushstring(L, (name + "_tread").c_str());
  lua_setfield(L, -2, "tread_set");
  return 1;
}

ParameterSpec positive(const char* key, const char* unit, const char* doc) {
  return {key, VT::Number, true, unit, doc, std::nullopt, Range::Positive};
}
ParameterSpec optional_non_negative(const char* key, const char* unit, const char* doc) {
  return {key, VT::Number, false, unit, doc, std::string("0"), Range::NonNegative};
}

/// Protected: parses the table at index 2 into the TireParameters at index 1.
int parse_tire_table(lua_State* L) {
  *static_cast<TireParameters*>(lua_touserdata(L, 1)) = tire_parameters(MacroArguments(L, 2, model_macro_spec("tire")));
  return 0;
}

/// Protected: the table of the tire property file named at index 1.
int read_tire_property_file(lua_State* L) { return push_tire_property_file(L, luaL_checkstring(L, 1)); }

}  // namespace

TireParameters load_tire_parameters(const std::string& source, const std::vector<ParameterValue>& overrides) {
  LuaSandbox sandbox(lua_module_dir());
  lua_State* L = sandbox.state();
  TireParameters parameters;
  lua_pushcfunction(L, parse_tire_table);
  lua_pushlightuserdata(L, &parameters);
  const bool property_file = source.size() > 4 && source.compare(source.size() - 4, 4, ".tir") == 0;
  if (property_file) require_regular_file(source);
  if (property_file)
    lua_pushcfunction(L, protected_call<read_tire_property_file>);
  else
    lua_getglobal(L, "require");
  lua_pushstring(L, source.c_str());
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) throw ModelError("tire parameters '" + source + "': " + error_text(L, -1));
  if (!lua_istable(L, -1)) throw ModelError("tire parameters '" + source + "': is not a parameter table");
  for (const ParameterValue& value : overrides) {
    // Whole numbers as Lua integers, so that integer keys (elements) take them.
    const double whole = std::nearbyint(value.second);
    if (whole == value.second && std::abs(whole) < 1e15)
      lua_pushinteger(L, static_cast<lua_Integer>(whole));
    else
      lua_pushnumber(L, value.second);
    lua_setfield(L, -2, value.first.c_str());
  }
  if (lua_pcall(L, 2, 0, 0) != LUA_OK) throw ModelError("tire parameters '" + source + "': " + error_text(L, -1));
  return parameters;
}

void add_tire_macros(MacroTable& table) {
  table.model_macros.push_back(
      {{"tire",
        "Builds a ring tire (docs/model.md section 1): a spindle node, N tread nodes on the outer circle, and N wedges "
        "of tread beam + sidewall + inflation pressure, with the rim and hub as mass and rotary inertia on the "
        "spindle; the tread rubber's stiffness and damping make its contact law with a road "
        "(model:tire_contact). Returns {name, spindle, tread, spindle_set, tread_set} (deck node numbers and set "
        "names). "
        "docs/tire.md explains every parameter and where the 145 SR-12 values come from.",
        {{"name", VT::String, false, "", "prefix of the tire's blocks and node sets", std::string("tire")},
         {"elements",
          VT::Integer,
          false,
          "",
          "number of wedges N",
          std::string("100"),
          Range::Positive,
          {},
          kMaxTireElements},
         positive("outer_diameter", "m", "unloaded, uninflated diameter at the tread nodes"),
         positive("rim_diameter", "m", "effective rim diameter"),
         positive("tread_width", "m", "width the inflation pressure acts on"),
         {"pressure", VT::Number, true, "Pa", "inflation pressure", std::nullopt, Range::NonNegative},
         {"pressure_load_function", VT::String, false, "", "load function scaling the pressure", std::string("ramp")},
         positive("sidewall_length", "m", "meridian cord length l_sw of one sidewall"),
         positive("tread_EA", "N", "tread axial stiffness"),
         positive("tread_GA", "N", "tread shear stiffness GA_s"),
         positive("tread_EI", "N m^2", "tread bending stiffness"),
         positive("tread_mass_per_length", "kg/m", "tread (belt) mass per length"),
         optional_non_negative("tread_rotary_inertia_per_length", "kg m", "tread rotary inertia per length"),
         optional_non_negative("tread_curvature_damping", "N m^2 s", "tread bending moment per curvature rate"),
         {"k_sw", VT::Number, true, "N m", "effective sidewall bending stiffness (both sidewalls)", std::nullopt,
          Range::NonNegative},
         {"k_sw_sign", VT::Number, false, "", "+1: eq. 9 as printed; -1: the physical bending direction",
          std::string("1")},
         {"k_gamma", VT::Number, true, "N/m", "sidewall shear stiffness per radian (both sidewalls)", std::nullopt,
          Range::NonNegative},
         optional_non_negative("sidewall_radial_damping", "N s/m^2", "dashpot along the cord, per length"),
         optional_non_negative("sidewall_circumferential_damping", "N s/m^2", "dashpot across the cord, per length"),
         optional_non_negative("tread_layer_radial_stiffness", "N/m^2",
                               "tread rubber: radial stiffness per length of circumference, the contact's normal "
                               "law (0: no tread rubber, no contact)"),
         optional_non_negative("tread_layer_circumferential_stiffness", "N/m^2",
                               "tread rubber: shear stiffness per length of circumference, the contact's tangential "
                               "law"),
         optional_non_negative("tread_layer_mass_per_length", "kg/m",
                               "tread rubber: mass per length, carried by the belt (the road side is massless)"),
         optional_non_negative("tread_layer_radial_damping", "N s/m^2",
                               "tread rubber: radial dashpot per length of circumference (hysteresis)"),
         optional_non_negative("tread_layer_circumferential_damping", "N s/m^2",
                               "tread rubber: shear dashpot per length of circumference"),
         positive("rim_mass", "kg", "rim and hub mass"),
         positive("rim_rotary_inertia", "kg m^2", "rim and hub rotary inertia"),
         {"x", VT::Number, false, "m", "spindle x", std::string("0")},
         {"y", VT::Number, false, "m", "spindle y", std::string("0")},
         {"heading",
          VT::String,
          false,
          "",
          "direction of travel over the road, the x axis of the spindle forces' ISO 8855 wheel axes (docs/output.md): "
          "+x on a road moving to -x, -x on a drum whose top moves to +x",
          std::string("+x"),
          Range::Any,
          {"+x", "-x"}}},
        "local tire = model:tire(require(\"tires.145SR12\"))"},
       tire_macro});
}

}  // namespace tirefe::macros
