// The `tirefe` command line: parses it, runs the deck, and says how the run ended. The
// process around it (tirefe, or tirefe-mpi on every MPI rank) prints the error and
// exits with the status.
//   tirefe deck.lua [key=value ...] [--output-dir DIR] [--restart FILE] [--quiet | --verbose]
//   tirefe --list-parameters DECK    the deck's parameters, without running it
//   tirefe --views RESULT.h5 ...    the field frames' views a run left out
//   tirefe --help | --macros | --version
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "deck/deck_session.hpp"

namespace tirefe::macros {

struct DeckOutcome {
  /// 0 success, 1 deck or model error, 2 usage error, 3 a self-check failed, 128 + signal
  /// when SIGINT or SIGTERM stopped the run (after closing its files).
  int status = 0;
  std::string error;  // for stderr, lines ending in '\n'; empty if none
  /// The files the run wrote (result files, checkpoints, XDMF indexes), by resolved path,
  /// also when it failed.
  std::vector<std::string> files = {};
};

/// Runs the command line; 'configure' (may be empty) adjusts the session before the deck
/// runs. SIGINT and SIGTERM stop the run while it runs (their handlers are restored after). Standard output gets
/// --help, --list-parameters, --macros, --version, the deck's own output and the self-check summary; standard error the
/// progress line on a terminal.
DeckOutcome run_deck_command(int argc, char** argv, const std::function<void(DeckSession&)>& configure);

}  // namespace tirefe::macros
