// The structural macros: building a model (nodes, sets, sections, beams, supports,
// loads, load functions) and driving its solution (integrator, Newton, step control,
// dt, step, solve, output, history, queries), plus tirefe.model, tirefe.check and
// tirefe.progress.
// Deck node numbers start at 1 (FEAP and Lua convention); the kernel counts from 0.
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>

#include "deck/deck_model.hpp"
#include "macros/macro_table.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

// ---- shared argument pieces ------------------------------------------------------

const ParameterSpec kNodeKey = node_key();
const ParameterSpec kSetKey = set_key();
const ParameterSpec kLoadFunctionKey{
    "load_function", VT::String, false, "", "name of the load function scaling the value", std::string("ramp")};
const std::vector<std::string> kDofNames = dof_names();

int component_of(const std::string& name) { return dof_component(name); }

// ---- building --------------------------------------------------------------------

int node_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const double x = arguments.number("x"), y = arguments.number("y");
  lua_pushinteger(L, deck.model().mesh().add_node({x, y}) + 1);
  return 1;
}

int node_set_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  std::vector<int> nodes;
  for (long long number : arguments.integer_list("nodes")) nodes.push_back(deck_node(deck, number));
  io::require_path_name(arguments.string("name"), "node set name");
  deck.model().mesh().define_node_set(arguments.string("name"), nodes);
  return 0;
}

int section_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  BeamSection section;
  section.axial_stiffness = arguments.number("EA");
  section.shear_stiffness = arguments.number("GA");
  section.bending_stiffness = arguments.number("EI");
  section.mass_per_length = arguments.number("rhoA");
  section.rotary_inertia_per_length = arguments.number("rhoI");
  section.curvature_damping = arguments.number("curvature_damping");
  deck.define_section(arguments.string("name"), section);
  return 0;
}

void add_beam(DeckModel& deck, const BeamSection& section, int start, int end) {
  Model& model = deck.model();
  auto* block = dynamic_cast<ElementBlockOf<TreadBeam>*>([&]() -> ElementBlock* {
    for (const auto& existing : model.blocks())
      if (existing->name() == "beams") return existing.get();
    return &model.add_block<TreadBeam>("beams");
  }());
  block->add({start, end}, TreadBeam(model.mesh().position(start), model.mesh().position(end), section));
}

int beam_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const BeamSection& section = deck.section(arguments.string("section"));
  const std::vector<long long> nodes = arguments.integer_list("nodes");
  const bool closed = arguments.boolean("closed");
  if (nodes.size() < 2) throw ModelError("a beam needs at least two nodes");
  const size_t count = closed ? nodes.size() : nodes.size() - 1;
  for (size_t i = 0; i < count; ++i)
    add_beam(deck, section, deck_node(deck, nodes[i]), deck_node(deck, nodes[(i + 1) % nodes.size()]));
  lua_pushinteger(L, static_cast<lua_Integer>(count));
  return 1;
}

int load_function_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const std::string name = arguments.string("name");
  if (arguments.has("points") == arguments.has("fn")) throw ModelError("give either 'points' or 'fn'");
  if (arguments.has("points")) {
    std::vector<std::pair<double, double>> points;
    for (const auto& row : arguments.number_matrix("points")) {
      if (row.size() != 2) throw ModelError("each load function point is {time, factor}");
      points.emplace_back(row[0], row[1]);
    }
    deck.define_load_function(name, LoadFunction::table(std::move(points)));
    return 0;
  }
  // A Lua function of time, kept in the registry; evaluated once per step and load.
  arguments.push_value("fn");
  const int reference = luaL_ref(L, LUA_REGISTRYINDEX);
  deck.note_lua_callback();
  deck.define_load_function(
      name, LoadFunction([L, reference, name](double time) {
        lua_rawgeti(L, LUA_REGISTRYINDEX, reference);
        lua_pushnumber(L, time);
        lua_call(L, 1, 1);
        int is_number = 0;
        const double factor = lua_tonumberx(L, -1, &is_number);
        lua_pop(L, 1);
        if (!is_number || !std::isfinite(factor))
          throw ModelError("load function '" + name + "' returned no finite number at t = " + std::to_string(time));
        return factor;
      }));
  return 0;
}

std::vector<int> components_of(const MacroArguments& arguments) {
  std::vector<int> components;
  for (const std::string& name : arguments.string_list("dofs")) components.push_back(component_of(name));
  return components;
}

int fix_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const std::vector<int> components =
      arguments.has("dofs") ? components_of(arguments) : std::vector<int>{kUx, kUy, kRz};
  for (int node : target_nodes(deck, arguments))
    for (int component : components) deck.model().fix(node, component);
  return 0;
}

int prescribe_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const int component = component_of(arguments.string("dof"));
  const int function = deck.load_function(arguments.string("load_function"));
  for (int node : target_nodes(deck, arguments))
    deck.model().prescribe(node, component, arguments.number("value"), function);
  return 0;
}

int release_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  for (int node : target_nodes(deck, arguments))
    for (int component : components_of(arguments)) deck.model().release(node, component);
  return 0;
}

int load_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const int function = deck.load_function(arguments.string("load_function"));
  const char* keys[kDofsPerNode] = {"fx", "fy", "mz"};
  bool any = false;
  for (int node : target_nodes(deck, arguments))
    for (int c = 0; c < kDofsPerNode; ++c)
      if (arguments.has(keys[c])) {
        deck.model().add_nodal_load(node, c, arguments.number(keys[c]), function);
        any = true;
      }
  if (!any) throw ModelError("give at least one of fx, fy, mz");
  return 0;
}

// ---- solution --------------------------------------------------------------------

int integrator_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  IntegratorParameters parameters;
  parameters.beta = arguments.number("beta");
  parameters.gamma = arguments.number("gamma");
  parameters.alpha = arguments.number("alpha");
  parameters.rho_inf = arguments.number("rho_inf");
  parameters.predictor = predictor_named(arguments.string("predictor"));
  deck.analysis().set_integrator(make_integrator(arguments.string("type"), parameters));
  return 0;
}

int newton_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  NewtonSettings& settings = deck.analysis().newton_settings();
  settings.residual_tolerance = arguments.number_or("tolerance", settings.residual_tolerance);
  settings.max_iterations = static_cast<int>(arguments.integer_or("max_iterations", settings.max_iterations));
  settings.budget_iterations = static_cast<int>(arguments.integer_or("budget_iterations", settings.budget_iterations));
  settings.budget_residual = arguments.number_or("budget_residual", settings.budget_residual);
  if (arguments.has("log"))
    deck.analysis().set_log(arguments.boolean("log") ? &deck.session().progress.output() : nullptr);
  return 0;
}

int step_control_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  StepControl& control = deck.analysis().step_control();
  control.min_step = arguments.number_or("min_dt", control.min_step);
  control.max_step = arguments.number_or("max_dt", control.max_step);
  control.max_cuts = static_cast<int>(arguments.integer_or("max_cuts", control.max_cuts));
  control.easy_iterations = static_cast<int>(arguments.integer_or("easy_iterations", control.easy_iterations));
  control.max_augmentations = static_cast<int>(arguments.integer_or("max_augmentations", control.max_augmentations));
  control.step_budget = static_cast<int>(arguments.integer_or("step_budget", control.step_budget));
  control.growth = arguments.number_or("growth", control.growth);
  if (control.growth < 1.0) throw ModelError("growth must be at least 1");
  return 0;
}

int dt_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  deck.analysis().set_time_step(arguments.number("value"));
  return 0;
}

int push_step_summary(lua_State* L, const std::vector<StepRecord>& records) {
  int iterations = 0, cuts = 0;
  for (const auto& record : records) {
    iterations += record.newton_iterations;
    cuts += record.cuts;
  }
  lua_createtable(L, 0, 4);
  lua_pushinteger(L, cuts);
  lua_setfield(L, -2, "cuts");
  lua_pushinteger(L, static_cast<lua_Integer>(records.size()));
  lua_setfield(L, -2, "steps");
  lua_pushinteger(L, iterations);
  lua_setfield(L, -2, "newton_iterations");
  lua_pushnumber(L, records.empty() ? 0.0 : records.back().time);
  lua_setfield(L, -2, "time");
  return 1;
}

int step_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  if (arguments.has("dt")) deck.analysis().set_time_step(arguments.number("dt"));
  return push_step_summary(L, deck.advance(0.0));
}

int solve_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  if (arguments.has("dt")) deck.analysis().set_time_step(arguments.number("dt"));
  const double now = deck.analysis().state().time, target = arguments.number("to");
  if (!(target > now))
    throw ModelError("'to' (" + std::to_string(target) + ") must be later than the current time " +
                     std::to_string(now));
  return push_step_summary(L, deck.advance(target - now));
}

// ---- output and queries ----------------------------------------------------------

int output_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  deck.open_output(arguments.string("file"), static_cast<int>(arguments.integer("fields_every")),
                   arguments.number("fields_interval"), arguments.boolean("views"));
  return 0;
}

using NodalQuantity = double (*)(const Analysis&, int dof);

NodalQuantity quantity_reader(const std::string& quantity) {
  if (quantity == "displacement") return [](const Analysis& a, int dof) { return a.state().displacement[dof]; };
  if (quantity == "velocity") return [](const Analysis& a, int dof) { return a.state().velocity[dof]; };
  if (quantity == "acceleration") return [](const Analysis& a, int dof) { return a.state().acceleration[dof]; };
  if (quantity == "reaction") return [](const Analysis& a, int dof) { return a.reactions()[dof]; };
  if (quantity == "position")  // the current position (reference + displacement; the rotation for rz)
    return [](const Analysis& a, int dof) {
      const int node = dof / kDofsPerNode, component = dof % kDofsPerNode;
      const double reference = component < 2 ? a.model().mesh().position(node)[component] : 0.0;
      return reference + a.state().displacement[dof];
    };
  return [](const Analysis& a, int dof) { return a.external_forces().size() ? a.external_forces()[dof] : 0.0; };
}

const char* quantity_unit(const std::string& quantity, int component) {
  static const char* units[5][3] = {
      {"m", "m", "rad"}, {"m/s", "m/s", "rad/s"}, {"m/s^2", "m/s^2", "rad/s^2"}, {"N", "N", "N m"}, {"N", "N", "N m"}};
  const char* names[4] = {"displacement", "velocity", "acceleration", "reaction"};
  if (quantity == "position") return units[0][component];
  int row = 4;
  for (int i = 0; i < 4; ++i)
    if (quantity == names[i]) row = i;
  return units[row][component];
}

/// Sum of a nodal quantity over the named nodes (a set's total reaction, say).
double summed_quantity(const Analysis& analysis, NodalQuantity reader, const std::vector<int>& nodes, int component) {
  double total = 0.0;
  for (int node : nodes) total += reader(analysis, dof_index(node, component));
  return total;
}

const std::vector<std::string> kNodalQuantities{"displacement", "velocity",       "acceleration",
                                                "reaction",     "external_force", "position"};
const std::vector<std::string> kQuantities{"displacement",   "velocity", "acceleration",  "reaction",
                                           "external_force", "position", "spindle_force", "spin_rate"};
const std::vector<std::string> kWheelComponents{"fx", "fz", "my"};

// ---- a tire's wheel quantities: ISO 8855 wheel axes (tire/wheel_axes.hpp) -----------

bool is_wheel_quantity(const std::string& quantity) { return quantity == "spindle_force" || quantity == "spin_rate"; }

using Reading = std::function<double(const Analysis&)>;

/// A tire's spindle force component (fx, fz, my) or spin rate in its wheel axes.
Reading wheel_reading(DeckModel& deck, const MacroArguments& arguments, const std::string& quantity) {
  if (arguments.has("dof"))
    throw ModelError("quantity \"" + quantity + "\" is in the tire's wheel axes: leave out 'dof'" +
                     (quantity == "spindle_force" ? " and give component = \"fx\", \"fz\" or \"my\"" : ""));
  if (!arguments.has("node")) throw ModelError("quantity \"" + quantity + "\" needs node = tire.spindle");
  const int spindle = deck_node(deck, arguments.integer("node"));
  const Heading heading = deck.wheel_heading(spindle);
  if (quantity == "spin_rate") {
    if (arguments.has("component")) throw ModelError("quantity \"spin_rate\" has no component: leave it out");
    return [spindle, heading](const Analysis& a) {
      return wheel_spin_rate(a.state().velocity[dof_index(spindle, kRz)], heading);
    };
  }
  if (!arguments.has("component"))
    throw ModelError("quantity \"spindle_force\" needs component = \"fx\", \"fz\" or \"my\"");
  const std::string component = arguments.string("component");
  const int row = component == "fx" ? 0 : component == "fz" ? 1 : 2;
  return [spindle, heading, row](const Analysis& a) {
    return wheel_load_from_reaction(a.reactions().segment<3>(dof_index(spindle, 0)), heading)[row];
  };
}

const char* wheel_unit(const std::string& quantity, const MacroArguments& arguments) {
  if (quantity == "spin_rate") return "rad/s";
  return arguments.string("component") == "my" ? "N m" : "N";
}

/// The nodal quantity of a history or value (summed over a set), or a tire's wheel quantity.
Reading reading_of(DeckModel& deck, const MacroArguments& arguments, const std::string& quantity) {
  if (is_wheel_quantity(quantity)) return wheel_reading(deck, arguments, quantity);
  if (arguments.has("component"))
    throw ModelError("'component' belongs to quantity = \"spindle_force\": give 'dof' for \"" + quantity + "\"");
  if (!arguments.has("dof")) throw ModelError("quantity \"" + quantity + "\" needs dof = \"ux\", \"uy\" or \"rz\"");
  const std::vector<int> nodes = target_nodes(deck, arguments);
  const int component = component_of(arguments.string("dof"));
  const NodalQuantity reader = quantity_reader(quantity);
  return [nodes, component, reader](const Analysis& a) { return summed_quantity(a, reader, nodes, component); };
}

/// A history channel of an element block's named response at one of its points
/// (core/element_response.hpp): the block answers by name.
void add_response_channel(DeckModel& deck, const MacroArguments& arguments) {
  for (const char* key : {"node", "set", "dof", "component"})
    if (arguments.has(key)) throw ModelError(std::string("'") + key + "' belongs to a nodal quantity: leave it out");
  if (!arguments.has("block")) throw ModelError("a response needs block = \"<element block name>\"");
  const std::string block = arguments.string("block"), name = arguments.string("response");
  const ElementResponses* responses = responses_of(deck.model().block(block));
  if (!responses) throw ModelError("element block '" + block + "' gives no named responses");
  const int index = responses->response_index(name);
  if (index < 0) {
    std::string names;
    for (const ResponseName& response : responses->response_names())
      names += (names.empty() ? "" : ", ") + response.name;
    throw ModelError("element block '" + block + "' has no response '" + name + "' (it has " + names + ")");
  }
  const long long point = arguments.integer("point");
  if (point > responses->response_points())
    throw ModelError("point " + std::to_string(point) + " of element block '" + block + "', which has " +
                     std::to_string(responses->response_points()));
  deck.output_or_default().add_channel(
      arguments.string("name"), responses->response_names()[index].unit,
      [responses, index, point = static_cast<int>(point - 1), scale = arguments.number("scale")](
          const State& state, const StepRecord&) { return scale * responses->response_value(index, point, state); });
}

int history_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  if (arguments.has("response")) {
    add_response_channel(deck, arguments);
    return 0;
  }
  if (arguments.has("block")) throw ModelError("'block' needs 'response'");
  const std::string quantity = arguments.string("quantity");
  const Reading reading = reading_of(deck, arguments, quantity);
  const std::string unit = is_wheel_quantity(quantity) ? wheel_unit(quantity, arguments)
                                                       : quantity_unit(quantity, component_of(arguments.string("dof")));
  const double scale = arguments.number("scale");
  const Analysis& analysis = deck.analysis();
  deck.output_or_default().add_channel(
      arguments.string("name"), unit,
      [reading, scale, &analysis](const State&, const StepRecord&) { return scale * reading(analysis); });
  return 0;
}

int history_values_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const std::vector<double> values = deck.output_or_default().history_values(arguments.string("name"));
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

int value_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const Reading reading = reading_of(deck, arguments, arguments.string("quantity"));
  deck.require_state("model:value");
  deck.model().finalize();
  const Analysis& analysis = deck.analysis();
  if (analysis.state().displacement.size() != deck.model().mesh().dof_count())
    throw ModelError("no step has been solved yet");
  lua_pushnumber(L, reading(analysis));
  return 1;
}

int result_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  io::ResultFile& output = deck.output_or_default();
  const std::string name = arguments.string("name");
  output.file().write_attribute("/results", name, arguments.number("value"));
  if (arguments.has("unit")) output.file().write_attribute("/results", name + "_unit", arguments.string("unit"));
  output.flush_if_due();
  return 0;
}

int time_macro(lua_State* L, DeckModel& deck, const MacroArguments&) {
  lua_pushnumber(L, deck.analysis().state().time);
  return 1;
}

int print_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const std::vector<int> nodes = target_nodes(deck, arguments);
  const NodalQuantity reader = quantity_reader(arguments.string("quantity"));
  deck.require_state("model:print");
  if (deck.analysis().state().displacement.size() != deck.model().mesh().dof_count())
    throw ModelError("no step has been solved yet");
  deck.session().progress.clear();
  std::printf("  %s at t = %g\n  %6s %14s %14s %14s\n", arguments.string("quantity").c_str(),
              deck.analysis().state().time, "node", "ux", "uy", "rz");
  for (int node : nodes)
    std::printf("  %6d %14.6e %14.6e %14.6e\n", node + 1, reader(deck.analysis(), dof_index(node, 0)),
                reader(deck.analysis(), dof_index(node, 1)), reader(deck.analysis(), dof_index(node, 2)));
  return 0;
}

// ---- module macros ---------------------------------------------------------------

int model_macro(lua_State* L, DeckSession& session, const MacroArguments& arguments) {
  push_new_model(L, arguments.string("title"), session);
  return 1;
}

int check_macro(lua_State*, DeckSession& session, const MacroArguments& arguments) {
  const std::string name = arguments.string("name");
  const double value = arguments.number("value"), expected = arguments.number("expected");
  const double allowed =
      arguments.has("relative") ? arguments.number("relative") * std::abs(expected) : arguments.number("tolerance");
  const bool passed = std::abs(value - expected) <= allowed;
  session.checks.push_back({name, passed});
  session.progress.clear();
  std::printf("  check %-40s %s: %.8g, expected %.8g +- %.3g\n", name.c_str(), passed ? "ok    " : "FAILED", value,
              expected, allowed);
  return 0;
}

int progress_macro(lua_State*, DeckSession& session, const MacroArguments& arguments) {
  session.progress.set_end_time(arguments.number("end_time"));
  return 0;
}

const ParameterSpec kDofsKey{
    "dofs",     VT::StringList, false, "", "DOFs to constrain", std::string("{\"ux\", \"uy\", \"rz\"}"),
    Range::Any, kDofNames};
const ParameterSpec kDofKey{"dof", VT::String, true, "", "DOF component", std::nullopt, Range::Any, kDofNames};
const ParameterSpec kNodalQuantityKey{
    "quantity", VT::String, false, "", "nodal quantity", std::string("displacement"), Range::Any, kNodalQuantities};
// history and value: a nodal quantity by DOF, or a tire's spindle force or spin rate in its wheel axes.
const ParameterSpec kQuantityDofKey{"dof",        VT::String, false,    "", "DOF component (nodal quantities)",
                                    std::nullopt, Range::Any, kDofNames};
const ParameterSpec kQuantityKey{"quantity",
                                 VT::String,
                                 false,
                                 "",
                                 "nodal quantity, or at node = tire.spindle the tire's spindle_force (give component) "
                                 "or spin_rate in ISO 8855 wheel axes (docs/output.md)",
                                 std::string("displacement"),
                                 Range::Any,
                                 kQuantities};
const ParameterSpec kComponentKey{"component",
                                  VT::String,
                                  false,
                                  "",
                                  "spindle_force: fx, fz [N] or my [N m], the force the tire exerts on the wheel",
                                  std::nullopt,
                                  Range::Any,
                                  kWheelComponents};

}  // namespace

const std::vector<std::string>& dof_names() {
  static const std::vector<std::string> names{"ux", "uy", "rz"};
  return names;
}

int dof_component(const std::string& name) {
  for (int c = 0; c < kDofsPerNode; ++c)
    if (dof_names()[c] == name) return c;
  throw ModelError("unknown DOF '" + name + "' (use ux, uy or rz)");
}

ParameterSpec node_key() { return {"node", VT::Integer, false, "", "node number (from 1)"}; }
ParameterSpec set_key() { return {"set", VT::String, false, "", "name of a node set (instead of node)"}; }

int deck_node(DeckModel& deck, long long number) {
  const int count = deck.model().mesh().node_count();
  if (number < 1 || number > count)
    throw ModelError("node " + std::to_string(number) + " does not exist (the model has " + std::to_string(count) +
                     " nodes, numbered from 1)");
  return static_cast<int>(number) - 1;
}

std::vector<int> target_nodes(DeckModel& deck, const MacroArguments& arguments) {
  const bool by_node = arguments.has("node"), by_set = arguments.has("set");
  if (by_node == by_set) throw ModelError("give either 'node' or 'set'");
  if (by_set) return deck.model().mesh().node_set(arguments.string("set"));
  return {deck_node(deck, arguments.integer("node"))};
}

void add_model_macros(MacroTable& table) {
  table.module_macros.push_back(
      {{"model",
        "Creates an empty model (a structure with its own mesh, solution and output). Returns the model; "
        "its macros are called with a colon, model:node{...}.",
        {{"title", VT::String, false, "", "a title written to the output", std::string("tirefe model")}},
        "local model = tirefe.model{ title = \"cantilever\" }"},
       model_macro});
  table.module_macros.push_back(
      {{"check",
        "Compares a computed value with an expected one; the run exits with status 3 if any check failed "
        "(self-checking decks). Give an absolute tolerance or a relative one.",
        {{"name", VT::String, true, "", "what is checked"},
         {"value", VT::Number, true, "", "the computed value"},
         {"expected", VT::Number, true, "", "the reference value"},
         {"tolerance", VT::Number, false, "", "allowed absolute difference", std::string("0"), Range::NonNegative},
         {"relative", VT::Number, false, "", "allowed difference relative to |expected|", std::nullopt,
          Range::NonNegative}},
        "tirefe.check{ name = \"tip deflection / L\", value = v, expected = 0.81061, tolerance = 1e-3 }"},
       check_macro});
  table.module_macros.push_back(
      {{"progress",
        "Says when the run ends, so that the progress line shown on a terminal can estimate the wall time "
        "left (tirefe --help). Without it the line shows the time spent only.",
        {{"end_time", VT::Number, true, "s", "the time of the model at the end of the run"}},
        "tirefe.progress{ end_time = 8.0 }"},
       progress_macro});

  auto add = [&table](MacroSpec spec, ModelHandler handler) {
    table.model_macros.push_back({std::move(spec), handler});
  };
  add({"node",
       "Adds a node at a reference position; returns its number (from 1).",
       {{"x", VT::Number, true, "m", "reference x"}, {"y", VT::Number, true, "m", "reference y"}},
       "local tip = model:node{ x = 1.0, y = 0.0 }"},
      node_macro);
  add({"node_set",
       "Names a list of nodes (supports, loads and output can then refer to the set).",
       {{"name", VT::String, true, "", "set name"}, {"nodes", VT::IntegerList, true, "", "node numbers"}},
       "model:node_set{ name = \"root\", nodes = {1} }"},
      node_set_macro);
  add({"section",
       "Defines a named beam section (the tread beam's properties).",
       {{"name", VT::String, true, "", "section name"},
        {"EA", VT::Number, true, "N", "axial stiffness", std::nullopt, Range::Positive},
        {"GA", VT::Number, true, "N", "shear stiffness GA_s", std::nullopt, Range::Positive},
        {"EI", VT::Number, true, "N m^2", "bending stiffness", std::nullopt, Range::Positive},
        {"rhoA", VT::Number, false, "kg/m", "mass per length", std::string("0"), Range::NonNegative},
        {"rhoI", VT::Number, false, "kg m", "rotary inertia per length", std::string("0"), Range::NonNegative},
        {"curvature_damping", VT::Number, false, "N m^2 s", "bending moment per curvature rate", std::string("0"),
         Range::NonNegative}},
       "model:section{ name = \"tread\", EA = 3e5, GA = 8e4, EI = 20, rhoA = 1.5 }"},
      section_macro);
  add({"beam",
       "Adds geometrically exact beam elements (Simo-Reissner, one-point quadrature) along a chain of nodes; "
       "closed = true also joins the last node to the first (a ring). Returns the number of elements added.",
       {{"section", VT::String, true, "", "section name"},
        {"nodes", VT::IntegerList, true, "", "chain of node numbers (2 for one element)"},
        {"closed", VT::Boolean, false, "", "close the chain into a ring", std::string("false")}},
       "model:beam{ section = \"tread\", nodes = {1, 2, 3, 4} }"},
      beam_macro);
  add({"load_function",
       "Defines a named load function of time scaling loads and prescribed values (FEAP's PROP). "
       "\"ramp\" (f = t) and \"constant\" (f = 1) always exist.",
       {{"name", VT::String, true, "", "load function name"},
        {"points", VT::NumberMatrix, false, "", "{time, factor} points, linear between, constant outside"},
        {"fn", VT::Function, false, "", "a Lua function of time (instead of points)"}},
       "model:load_function{ name = \"hold\", points = {{0, 0}, {1, 1}, {5, 1}} }"},
      load_function_macro);
  add({"fix",
       "Fixes DOFs of a node or a node set (zero displacement).",
       {kNodeKey, kSetKey, kDofsKey},
       "model:fix{ set = \"root\", dofs = {\"ux\", \"uy\", \"rz\"} }"},
      fix_macro);
  add({"prescribe",
       "Prescribes a DOF's displacement: value * load_function(t).",
       {kNodeKey, kSetKey, kDofKey, {"value", VT::Number, true, "m or rad", "displacement scale"}, kLoadFunctionKey},
       "model:prescribe{ node = 3, dof = \"uy\", value = -0.02 }"},
      prescribe_macro);
  add({"release",
       "Frees DOFs that were fixed or prescribed.",
       {kNodeKey, kSetKey, {"dofs", VT::StringList, true, "", "DOFs to free", std::nullopt, Range::Any, kDofNames}},
       "model:release{ node = 1, dofs = {\"rz\"} }"},
      release_macro);
  add({"load",
       "Applies nodal forces and moments scaled by a load function (default ramp: f = t).",
       {kNodeKey,
        kSetKey,
        {"fx", VT::Number, false, "N", "force along x"},
        {"fy", VT::Number, false, "N", "force along y"},
        {"mz", VT::Number, false, "N m", "moment about z"},
        kLoadFunctionKey},
       "model:load{ node = tip, fy = -10.0 }"},
      load_macro);
  add({"integrator",
       "Chooses the solution procedure: quasi-static or a generalized-alpha preset (docs/dynamics.md).",
       {{"type", VT::String, true, "", "quasi-static or a generalized-alpha preset", std::nullopt, Range::Any,
         integrator_names()},
        {"beta", VT::Number, false, "", "Newmark beta", std::string("0.25"), Range::Positive},
        {"gamma", VT::Number, false, "", "Newmark gamma", std::string("0.5"), Range::Positive},
        {"alpha", VT::Number, false, "", "HHT alpha in [-1/3, 0]", std::string("-0.05")},
        {"rho_inf", VT::Number, false, "", "wbz and generalized_alpha: spectral radius at omega h -> infinity, [0, 1]",
         std::string("0.9")},
        {"predictor", VT::String, false, "",
         "start of each step: same_acceleration (smooth motion), zero_acceleration (accelerations that jump, "
         "as in a contact patch rolling at speed) or same_displacement",
         std::string("same_acceleration"), Range::Any, predictor_names()}},
       "model:integrator{ type = \"hht\", alpha = -0.1 }"},
      integrator_macro);
  add({"newton",
       "Newton-Raphson settings.",
       {{"tolerance", VT::Number, false, "", "on |R| / R_ref", std::string("1e-9"), Range::Positive},
        {"max_iterations", VT::Integer, false, "", "per step before the step is cut", std::string("25"),
         Range::Positive},
        {"budget_iterations", VT::Integer, false, "",
         "a step budget: after this many iterations a step whose |R| / R_ref is within budget_residual is taken "
         "unconverged, its residual in the history channel 'residual' (0: none)",
         std::string("0"), Range::NonNegative},
        {"budget_residual", VT::Number, false, "", "the largest |R| / R_ref a step budget ends a step with",
         std::string("1e-4"), Range::Positive},
        {"log", VT::Boolean, false, "", "print every iteration's residual norm", std::string("false")}},
       "model:newton{ tolerance = 1e-10, log = true }"},
      newton_macro);
  add({"step_control",
       "Automatic step cutting and growth.",
       {{"min_dt", VT::Number, false, "s", "smallest step before giving up", std::string("0"), Range::NonNegative},
        {"max_dt", VT::Number, false, "s", "largest step (0: the nominal dt)", std::string("0"), Range::NonNegative},
        {"max_cuts", VT::Integer, false, "", "halvings of one step", std::string("10"), Range::NonNegative, {}, 50},
        {"easy_iterations", VT::Integer, false, "", "grow the step after converging in this many iterations",
         std::string("4"), Range::NonNegative},
        {"growth", VT::Number, false, "", "growth factor back toward dt", std::string("2"), Range::Positive},
        {"max_augmentations", VT::Integer, false, "", "contact multiplier updates per step (0: penalty only)",
         std::string("20"), Range::NonNegative},
        {"step_budget", VT::Integer, false, "",
         "steps one model:step or model:solve may take per nominal step it spans, plus as many again; the run "
         "stops with an error past it (0: no budget)",
         std::string("100"), Range::NonNegative}},
       "model:step_control{ max_cuts = 6 }"},
      step_control_macro);
  add({"dt",
       "Sets the nominal time (or load) step (FEAP's DT).",
       {{"value", VT::Number, true, "s", "step", std::nullopt, Range::Positive}},
       "model:dt{ value = 0.1 }"},
      dt_macro);
  add({"step",
       "Solves one step of dt with Newton iterations (FEAP's TIME + LOOP/TANG/NEXT), cutting it if needed. "
       "Returns {steps, newton_iterations, cuts, time}.",
       {{"dt", VT::Number, false, "s", "new nominal step", std::nullopt, Range::Positive}},
       "model:step()"},
      step_macro);
  add({"solve",
       "Advances to time 'to' in steps of dt. Returns {steps, newton_iterations, cuts, time}.",
       {{"to", VT::Number, true, "s", "end time"},
        {"dt", VT::Number, false, "s", "new nominal step", std::nullopt, Range::Positive}},
       "model:solve{ to = 1.0, dt = 0.1 }"},
      solve_macro);
  add({"output",
       "Opens the model's HDF5 result file (docs/output.md); a relative path lands in the output folder "
       "(--output-dir, default results/). Without this call the first step opens <deck name>.h5.",
       {{"file", VT::String, true, "", "file name"},
        {"fields_every", VT::Integer, false, "", "write displacement fields every n steps (0: never)", std::string("0"),
         Range::NonNegative},
        {"fields_interval", VT::Number, false, "s",
         "write displacement fields every this much time, whatever the step sizes (0: never)", std::string("0"),
         Range::NonNegative},
        {"views", VT::Boolean, false, "",
         "make the frames' views for the XDMF index during the run (false: `tirefe --views FILE` makes them)",
         std::string("true")}},
       "model:output{ file = \"cantilever.h5\", fields_every = 1 }"},
      output_macro);
  add({"history",
       "Adds a history channel written at every step: a nodal quantity (summed over a set), a tire's spindle "
       "force or spin rate in ISO 8855 wheel axes, or a named response of an element block at one of its points "
       "(a contact block's gap, normal_force, tangential_force, state, coordinate or sliding_velocity; "
       "docs/output.md).",
       {{"name", VT::String, true, "", "channel name (/history/<name>)"},
        kNodeKey,
        kSetKey,
        kQuantityDofKey,
        kQuantityKey,
        kComponentKey,
        {"block", VT::String, false, "", "element block whose response is recorded (with 'response')"},
        {"response", VT::String, false, "", "name of the block's response, in the unit the block gives"},
        {"point", VT::Integer, false, "", "the block's point, from 1: its elements' points in order", std::string("1"),
         Range::Positive},
        {"scale", VT::Number, false, "", "factor on the value (-1: the force on a support instead of its reaction)",
         std::string("1")}},
       "model:history{ name = \"spindle_fz\", node = tire.spindle, quantity = \"spindle_force\", component = \"fz\" }"},
      history_macro);
  add({"history_values",
       "Returns the values a history channel recorded so far, one per accepted step, as a list (name = \"time\": "
       "their times; the step channels of docs/output.md and the deck's model:history{...} channels).",
       {{"name", VT::String, true, "", "channel name (/history/<name>)"}},
       "local fz = model:history_values{ name = \"spindle_fz\" }"},
      history_values_macro);
  add({"value",
       "Returns a nodal quantity at the current time (summed over a set), or a tire's spindle force or spin rate.",
       {kNodeKey, kSetKey, kQuantityDofKey, kQuantityKey, kComponentKey},
       "local v = model:value{ node = tip, dof = \"uy\" }"},
      value_macro);
  add({"result",
       "Records a scalar result of the run (a peak force, a frequency) as an attribute of /results in the "
       "result file, for post-processing and sweeps.",
       {{"name", VT::String, true, "", "attribute name"},
        {"value", VT::Number, true, "", "value"},
        {"unit", VT::String, false, "", "unit, stored as the attribute <name>_unit"}},
       "model:result{ name = \"fz_on_top_Hz\", value = 88.0, unit = \"Hz\" }"},
      result_macro);
  add({"time", "Returns the current time.", {}, "local t = model:time()"}, time_macro);
  add({"print",
       "Prints a nodal quantity for a node or a set (FEAP's DISP).",
       {kNodeKey, kSetKey, kNodalQuantityKey},
       "model:print{ set = \"tip\" }"},
      print_macro);
}

}  // namespace tirefe::macros
