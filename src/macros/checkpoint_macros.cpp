// Checkpoint macro (FEAP's SAVE): the run's complete state, for `tirefe deck.lua --restart FILE`
// (docs/restart.md).
#include "deck/deck_model.hpp"
#include "macros/macro_table.hpp"

namespace tirefe::macros {

namespace {

using VT = ValueType;

int checkpoint_macro(lua_State*, DeckModel& deck, const MacroArguments& arguments) {
  const std::string file = arguments.string("file");
  const int steps = static_cast<int>(arguments.integer("every_steps"));
  const double minutes = arguments.number("every_minutes");
  if (steps > 0 || minutes > 0.0)
    deck.schedule_checkpoints(file, steps, minutes);
  else
    deck.write_checkpoint(file);
  return 0;
}

}  // namespace

void add_checkpoint_macros(MacroTable& table) {
  table.model_macros.push_back(
      {{"checkpoint",
        "Writes the run's complete state (u, v, a, time, step size, element and contact history, energy "
        "bookkeeping, and the result file's rows) to an HDF5 checkpoint: now, after the last accepted step, or "
        "with every_steps / every_minutes from then on after every n steps and every m minutes of wall time "
        "(the file is replaced each time). `tirefe deck.lua --restart FILE` continues from it, bit for bit "
        "(docs/restart.md). A relative path lands in the output folder.",
        {{"file", VT::String, true, "", "checkpoint file name"},
         {"every_steps", VT::Integer, false, "", "write after every n accepted steps (0: not by steps)",
          std::string("0"), Range::NonNegative},
         {"every_minutes", VT::Number, false, "min", "write every m minutes of wall time (0: not by time)",
          std::string("0"), Range::NonNegative}},
        "model:checkpoint{ file = \"drum.ckpt.h5\", every_steps = 500, every_minutes = 10 }"},
       checkpoint_macro});
}

}  // namespace tirefe::macros
