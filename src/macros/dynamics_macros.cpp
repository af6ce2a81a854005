// Dynamics macros: initial conditions and modal analysis (FEAP's EIGE).
#include <cstdio>

#include "macros/deck_model.hpp"
#include "macros/macro_table.hpp"
#include "solvers/modal.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

int initial_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const int component = dof_component(arguments.string("dof"));
  if (!arguments.has("displacement") && !arguments.has("velocity"))
    throw ModelError("give a displacement, a velocity, or both");
  deck.model().finalize();
  for (int node : target_nodes(deck, arguments)) {
    const int dof = dof_index(node, component);
    if (arguments.has("displacement")) deck.analysis().set_initial_displacement(dof, arguments.number("displacement"));
    if (arguments.has("velocity")) deck.analysis().set_initial_velocity(dof, arguments.number("velocity"));
  }
  return 0;
}

int modal_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const int count = static_cast<int>(arguments.integer("modes"));
  deck.require_state("model:modal");
  const ModalResult result = modal_analysis(deck.analysis(), count);
  const std::string label = arguments.string_or("label", "t" + std::to_string(deck.analysis().state().time));
  deck.output_or_default().write_modes(label, deck.analysis(), result.frequencies_hz, result.rigid_body,
                                       result.shapes);
  if (!deck.session().quiet) {
    std::printf("  modal analysis at t = %g (%s):\n", deck.analysis().state().time, label.c_str());
    for (size_t i = 0; i < result.frequencies_hz.size(); ++i)
      std::printf("    mode %3zu  %12.4f Hz%s\n", i + 1, result.frequencies_hz[i],
                  result.rigid_body[i] ? "  (rigid-body mode)" : "");
  }
  lua_createtable(L, static_cast<int>(result.frequencies_hz.size()), 0);
  for (size_t i = 0; i < result.frequencies_hz.size(); ++i) {
    lua_pushnumber(L, result.frequencies_hz[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

}  // namespace

void add_dynamics_macros(MacroTable& table) {
  table.model_macros.push_back(
      {{"initial",
        "Sets initial displacement and/or velocity of a DOF of a node or a set before the first dynamic step; "
        "the initial acceleration is then computed from equilibrium.",
        {node_key(), set_key(),
         {"dof", VT::String, true, "", "DOF component", std::nullopt, Range::Any, dof_names()},
         {"displacement", VT::Number, false, "m or rad", "initial displacement"},
         {"velocity", VT::Number, false, "m/s or rad/s", "initial velocity"}},
        "model:initial{ set = \"tip\", dof = \"uy\", velocity = 2.0 }"},
       initial_macro});
  table.model_macros.push_back(
      {{"modal",
        "Modal analysis of the linearised system at the current state (tangent stiffness including geometric and "
        "contact terms, prescribed DOFs held): the lowest natural frequencies and mode shapes, printed, written "
        "to /modes/<label> of the output, and returned as a list of frequencies in Hz (0 for rigid-body modes).",
        {{"modes", VT::Integer, true, "", "number of modes", std::nullopt, Range::Positive},
         {"label", VT::String, false, "", "name of the /modes group (default: the time)"}},
        "local f = model:modal{ modes = 10, label = \"loaded\" }"},
       modal_macro});
}

}  // namespace tirefe::macros
