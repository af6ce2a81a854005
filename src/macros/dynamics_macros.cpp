// Dynamics macros: initial conditions and modal analysis (FEAP's EIGE).
#include <complex>
#include <cstdio>

#include "deck/deck_model.hpp"
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

/// Pushes a Lua list of numbers.
void push_numbers(lua_State* L, const std::vector<double>& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

/// Pushes per mode {fx, fy, mz} of 'node' from a dof_count x modes table.
template <class Reactions, class Value>
void push_reactions(lua_State* L, int node, const Reactions& reactions, Value value) {
  lua_createtable(L, static_cast<int>(reactions.cols()), 0);
  for (Eigen::Index i = 0; i < reactions.cols(); ++i) {
    lua_createtable(L, kDofsPerNode, 0);
    for (int c = 0; c < kDofsPerNode; ++c) {
      lua_pushnumber(L, value(reactions(dof_index(node, c), i)));
      lua_rawseti(L, -2, c + 1);
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

/// The modes as the result file's /modes/<label> holds them.
io::ModeTable mode_table(const Analysis& analysis, const ModalResult& modes) {
  io::ModeTable table;
  table.time = analysis.state().time;
  table.frequencies_hz = modes.frequencies_hz;
  table.rigid_body = modes.rigid_body;
  table.shapes = modes.shapes;
  return table;
}
io::ModeTable mode_table(const Analysis& analysis, const DampedModalResult& modes) {
  io::ModeTable table;
  table.time = analysis.state().time;
  table.frequencies_hz = modes.frequencies_hz;
  table.rigid_body = modes.rigid_body;
  table.shapes = modes.shapes.real();
  table.damped = true;
  table.spin_rate = modes.spin_rate;
  table.damping_ratios = modes.damping_ratios;
  table.natural_frequencies_hz = modes.natural_frequencies_hz;
  table.shapes_imag = modes.shapes.imag();
  return table;
}

int undamped_modes(lua_State* L, DeckModel& deck, const MacroArguments& arguments, const std::string& label,
                   int count) {
  const ModalResult result = modal_analysis(deck.analysis(), count);
  deck.output_or_default().write_modes(label, deck.model(), mode_table(deck.analysis(), result));
  if (!deck.session().quiet) {
    deck.session().progress.clear();
    std::printf("  modal analysis at t = %g (%s):\n", deck.analysis().state().time, label.c_str());
    for (size_t i = 0; i < result.frequencies_hz.size(); ++i)
      std::printf("    mode %3zu  %12.4f Hz%s\n", i + 1, result.frequencies_hz[i],
                  result.rigid_body[i] ? "  (rigid-body mode)" : "");
  }
  push_numbers(L, result.frequencies_hz);
  if (!arguments.has("reaction_node")) return 1;
  // Per mode {fx, fy, mz}: the support reaction K phi of the mass-normalised shape.
  push_reactions(L, deck_node(deck, arguments.integer("reaction_node")), result.reactions,
                 [](double force) { return force; });
  return 2;
}

int damped_modes(lua_State* L, DeckModel& deck, const MacroArguments& arguments, const std::string& label, int count) {
  DampedModalSettings settings;
  settings.damping = arguments.boolean("damped");
  settings.spin_rate = arguments.number_or("spin_rate", 0.0);
  const DampedModalResult result = damped_modal_analysis(deck.analysis(), count, settings);
  deck.output_or_default().write_modes(label, deck.model(), mode_table(deck.analysis(), result));
  const int node = arguments.has("reaction_node") ? deck_node(deck, arguments.integer("reaction_node")) : -1;
  if (!deck.session().quiet) {
    deck.session().progress.clear();
    std::printf("  %s modal analysis at t = %g (%s)", settings.damping ? "damped" : "undamped",
                deck.analysis().state().time, label.c_str());
    if (settings.spin_rate != 0.0) std::printf(", frame turning at %g rad/s", settings.spin_rate);
    std::printf(":\n    mode    frequency    zeta        natural%s\n",
                node >= 0 ? "      axle |Fx|      |Fy| [N]" : "");
    for (size_t i = 0; i < result.frequencies_hz.size(); ++i) {
      std::printf("    %4zu %10.4f Hz %8.5f %10.4f Hz", i + 1, result.frequencies_hz[i], result.damping_ratios[i],
                  result.natural_frequencies_hz[i]);
      if (node >= 0)
        std::printf("  %10.4g %10.4g", std::abs(result.reactions(dof_index(node, kUx), i)),
                    std::abs(result.reactions(dof_index(node, kUy), i)));
      std::printf("%s\n", result.rigid_body[i] ? "  (rigid-body mode)" : "");
    }
  }
  push_numbers(L, result.frequencies_hz);
  // Per mode {|fx|, |fy|, |mz|}: the amplitude of the complex support reaction.
  if (node >= 0)
    push_reactions(L, node, result.reactions, [](std::complex<double> force) { return std::abs(force); });
  else
    lua_pushnil(L);
  push_numbers(L, result.damping_ratios);
  return 3;
}

int modal_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const int count = static_cast<int>(arguments.integer("modes"));
  deck.require_state("model:modal");
  // The analyses return the modes there are, at most as many as the free equations: a
  // deck asking for more would get fewer than it counts on without a word.
  deck.model().finalize();
  const int equations = deck.model().dof_map().equation_count();
  if (count > equations)
    throw ModelError("modal analysis: " + std::to_string(count) + " modes asked of a model with " +
                     std::to_string(equations) + " free equations (at most that many modes)");
  const std::string label = arguments.string_or("label", "t" + std::to_string(deck.analysis().state().time));
  io::require_path_name(label, "modal label");
  if (arguments.boolean("damped") || arguments.has("spin_rate")) return damped_modes(L, deck, arguments, label, count);
  return undamped_modes(L, deck, arguments, label, count);
}

}  // namespace

void add_dynamics_macros(MacroTable& table) {
  table.model_macros.push_back(
      {{"initial",
        "Sets initial displacement and/or velocity of a DOF of a node or a set before the first dynamic step; "
        "the initial acceleration is then computed from equilibrium.",
        {node_key(),
         set_key(),
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
        "tire mode on a fixed axle. With damped = true (or a spin_rate) the damped modes instead: the quadratic "
        "eigenproblem with the damping matrix, modes in ascending |lambda|, one per complex pair and one per real "
        "(overdamped) root; it returns the damped frequencies Im(lambda)/2pi (0 for real roots), the reactions "
        "as amplitudes {|fx|, |fy|, |mz|} of the complex (K + lambda C + lambda^2 M) phi (nil without "
        "reaction_node) and a third list, the damping ratios -Re(lambda)/|lambda|; /modes/<label> then also holds "
        "damping_ratio, natural_frequency and shapes_imag. A spin_rate linearises in the frame turning with the "
        "tire (state from a run rolling at that spin): Coriolis and centrifugal terms, frequencies in that frame "
        "(docs/dynamics.md).",
        {{"modes", VT::Integer, true, "", "number of modes", std::nullopt, Range::Positive},
         {"label", VT::String, false, "", "name of the /modes group (default: the time)"},
         {"reaction_node", VT::Integer, false, "", "node whose support reaction per mode is returned", std::nullopt,
          Range::Positive},
         {"damped", VT::Boolean, false, "", "include the damping matrix (the quadratic eigenproblem)",
          std::string("false")},
         {"spin_rate", VT::Number, false, "rad/s",
          "spin about z of the frame the modes are computed in (counter-clockwise positive); without damped = true "
          "the damping is left out"}},
        "local f, r, zeta = model:modal{ modes = 10, damped = true, spin_rate = 52.5, reaction_node = tire.spindle }"},
       modal_macro});
}

}  // namespace tirefe::macros
