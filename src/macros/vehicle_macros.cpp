// The vehicle macros: the spindle force of a tire driven from the deck (docs/spindle.md).
//
// A model's driven spindles are kept per node in a registry that lives in a step
// observer of the model's analysis, so it dies with the model (as the contact surfaces do).
#include <map>
#include <memory>

#include "macros/deck_model.hpp"
#include "macros/macro_table.hpp"
#include "vehicle/tire_spindle.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

struct SpindleRegistry {
  std::map<int, std::unique_ptr<TireSpindle>> spindles;  // by 0-based spindle node
};

SpindleRegistry& spindles_of(DeckModel& deck) {
  static std::map<const DeckModel*, std::weak_ptr<SpindleRegistry>> registries;
  if (auto live = registries[&deck].lock()) return *live;
  auto created = std::make_shared<SpindleRegistry>();
  deck.analysis().add_step_observer([created](const Analysis&, const StepRecord&) {});  // owns the registry
  registries[&deck] = created;
  return *created;
}

void push_row(lua_State* L, const double* values) {
  lua_createtable(L, 3, 0);
  for (int j = 0; j < 3; ++j) {
    lua_pushnumber(L, values[j]);
    lua_rawseti(L, -2, j + 1);
  }
}

int spindle_force_macro(lua_State* L, DeckModel& deck, const MacroArguments& arguments) {
  const int node = deck_node(deck, arguments.integer("node"));
  const SpinMode spin = arguments.has("spin") ? SpinMode::Driven : SpinMode::Free;
  auto& spindles = spindles_of(deck).spindles;
  auto& spindle = spindles[node];
  if (!spindle) {
    spindle = std::make_unique<TireSpindle>(deck.analysis(), node, spin);
  } else if (spindle->spin() != spin) {
    throw ModelError(std::string("this spindle was first driven with ") +
                     (spindle->spin() == SpinMode::Free ? "a free spin: leave out 'spin'" : "its spin: give 'spin'"));
  }
  deck.output_or_default();  // accepted steps are written like any other
  SpindleInput input;
  input.time_step = arguments.number("dt");
  input.x = arguments.number("x");
  input.y = arguments.number("y");
  input.spin = spin == SpinMode::Driven ? arguments.number("spin") : 0.0;
  const SpindleReply reply = spindle->solve_step(input);
  if (arguments.boolean("commit")) spindle->commit();

  lua_createtable(L, 0, 7);
  const char* names[] = {"fx", "fy", "mz"};
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, reply.force[i]);
    lua_setfield(L, -2, names[i]);
  }
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    push_row(L, reply.jacobian[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "jacobian");
  lua_pushnumber(L, reply.time);
  lua_setfield(L, -2, "time");
  lua_pushinteger(L, reply.newton_iterations);
  lua_setfield(L, -2, "newton_iterations");
  return 1;
}

}  // namespace

void add_vehicle_macros(MacroTable& table) {
  table.model_macros.push_back(
      {{"spindle_force",
        "Solves one dynamic step of the tire with its spindle held at {x, y} (and turned to 'spin', or spinning "
        "freely without it) at the end of the step, and returns the force that holds it there and its Jacobian "
        "(MODEL.md section 6): {fx, fy, mz, jacobian = 3x3 d(fx, fy, mz)/d(x, y, spin), time, "
        "newton_iterations}. The step stays a trial (calling again re-solves it from the same state) until "
        "'commit' accepts it. The model's integrator must be dynamic; docs/spindle.md.",
        {{"node", VT::Integer, true, "", "the tire's spindle node (tire.spindle)", std::nullopt, Range::Positive},
         {"x", VT::Number, true, "m", "spindle centre x at the end of the step (absolute)"},
         {"y", VT::Number, true, "m", "spindle centre y at the end of the step (absolute)"},
         {"spin", VT::Number, false, "rad", "spindle rotation from the reference, counter-clockwise (none: free spin)"},
         {"dt", VT::Number, true, "s", "time step from the committed time", std::nullopt, Range::Positive},
         {"commit", VT::Boolean, false, "", "accept the step after solving it", std::string("false")}},
        "local s = model:spindle_force{ node = tire.spindle, x = 0, y = -0.02, dt = 1e-3, commit = true }"},
       spindle_force_macro});
}

}  // namespace tirefe::macros
