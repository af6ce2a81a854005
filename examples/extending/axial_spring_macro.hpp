// model:axial_spring{ nodes = {a, b}, stiffness = k }: the worked macro of
// docs/extending.md, which adds an AxialSpring between two deck nodes. A macro is a spec
// (its keys, checked before the handler runs, and its reference text) and a handler.
#pragma once

#include <string>
#include <vector>

#include "examples/extending/axial_spring.hpp"
#include "deck/deck_model.hpp"
#include "macros/macro_table.hpp"

namespace tirefe::examples {

inline const macros::MacroSpec& axial_spring_spec() {
  using macros::Range;
  using macros::ValueType;
  static const macros::MacroSpec spec{
      "axial_spring",
      "A linear spring between two nodes, acting along the line joining them as they move (a truss bar). "
      "Returns the number of springs in the model's block 'springs'.",
      {{"nodes", ValueType::IntegerList, true, "", "the two end nodes {a, b}"},
       {"stiffness", ValueType::Number, true, "N/m", "spring stiffness k", std::nullopt, Range::Positive}},
      "model:axial_spring{ nodes = { 1, 2 }, stiffness = 2e4 }"};
  return spec;
}

inline int axial_spring_macro(lua_State* L, macros::DeckModel& deck, const macros::MacroArguments& arguments) {
  const std::vector<long long> nodes = arguments.integer_list("nodes");
  if (nodes.size() != 2) throw ModelError("'nodes' takes two node numbers {a, b}");
  const int a = macros::deck_node(deck, nodes[0]), b = macros::deck_node(deck, nodes[1]);
  Model& model = deck.model();
  ElementBlockOf<AxialSpring>* springs = nullptr;
  for (const auto& block : model.blocks())
    if (block->name() == "springs" && !(springs = dynamic_cast<ElementBlockOf<AxialSpring>*>(block.get())))
      throw ModelError("the model has an element block 'springs' of another kind");
  if (!springs) springs = &model.add_block<AxialSpring>("springs");
  springs->add({a, b}, AxialSpring(model.mesh().position(a), model.mesh().position(b), arguments.number("stiffness")));
  lua_pushinteger(L, springs->size());
  return 1;
}

}  // namespace tirefe::examples
