// tirefe: runs an input deck in this process (docs/decks.md).
//   tirefe deck.lua [key=value ...] [--output-dir DIR] [--restart FILE] [--quiet | --verbose]
//   tirefe --list-parameters DECK    the deck's parameters, without running it
//   tirefe --views RESULT.h5 ...    the field frames' views a run left out
//   tirefe --help | --macros | --version
// Exit status: 0 success, 1 deck or model error, 2 usage error, 3 a self-check failed,
// 128 + signal when SIGINT or SIGTERM stopped the run (after closing its files).
#include <iostream>

#include "app/deck_runner.hpp"
#include "app/program_heap.hpp"

int main(int argc, char** argv) {
  tirefe::macros::keep_row_buffers_in_heap();
  const tirefe::macros::DeckOutcome outcome = tirefe::macros::run_deck_command(argc, argv, {});
  std::cerr << outcome.error;
  return outcome.status;
}
