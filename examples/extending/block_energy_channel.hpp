// The worked output quantity of docs/extending.md: a history channel of the result file,
// /history/<block>_strain_energy [J], holding the strain energy an element block stores
// at every accepted step (ElementBlock::energy, summed over its elements).
#pragma once

#include <string>

#include "io/result_file.hpp"

namespace tirefe::examples {

/// Adds the channel for the block 'name' of the analysis's model; ModelError if there is none.
inline void add_strain_energy_channel(io::ResultFile& file, const Model& model, const std::string& name) {
  const ElementBlock& block = model.block(name);
  file.add_channel(name + "_strain_energy", "J",
                   [&block](const State& state, const StepRecord&) { return block.energy(state).strain; });
}

}  // namespace tirefe::examples
