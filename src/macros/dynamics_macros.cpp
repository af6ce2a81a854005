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
  if (!arguments.has("reaction_node")) return 1;
  // Per mode {fx, fy, mz}: the support reaction K_pf phi of the mass-normalised shape.
  const int node = deck_node(deck, arguments.integer("reaction_node"));
  lua_createtable(L, static_cast<int>(result.frequencies_hz.size()), 0);
  for (Eigen::Index i = 0; i < result.reactions.cols(); ++i) {
    lua_createtable(L, kDofsPerNode, 0);
    for (int c = 0; c < kDofsPerNode; ++c) {
      lua_pushnumber(L, result.reactions(dof_index(node, c), i));
      lua_rawseti(L, -2, c + 1);
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 2;
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
        "to /modes/<label> of the output, and returned as a list of frequencies in Hz (0 for rigid-body modes). "
        "With reaction_node, a second list gives per mode {fx, fy, mz}: the support reaction K phi that the "
        "mass-normalised shape puts on that node's prescribed DOFs (0 on free ones), e.g. the spindle force of a "
        "tire mode on a fixed axle.",
        {{"modes", VT::Integer, true, "", "number of modes", std::nullopt, Range::Positive},
         {"label", VT::String, false, "", "name of the /modes group (default: the time)"},
         {"reaction_node", VT::Integer, false, "", "node whose support reaction per mode is returned",
          std::nullopt, Range::Positive}},
        "local f, r = model:modal{ modes = 10, label = \"loaded\", reaction_node = tire.spindle }"},
       modal_macro});
}

}  // namespace tirefe::macros
