// Runs a deck in this process with every macro installed, for tests of deck-level
// features that need no separate process (file readers, geometry checks).
#pragma once

#include <catch2/catch.hpp>

#include <functional>
#include <string>

#include "deck/deck_session.hpp"
#include "deck/lua_sandbox.hpp"
#include "macros/macro_table.hpp"
#include "tirefe/test_paths.hpp"

namespace tirefe::testing {

struct InProcessRun {
  std::string error;  // the deck error ("" if the deck ran to its end)
  int checks = 0;     // tirefe.check calls
  int failed_checks = 0;
};

/// 'prepare' may add to the sandbox once the macros are installed (a macro of a test's own).
inline InProcessRun run_deck_in_process(const std::string& deck, const std::string& output_dir,
                                        const std::function<void(macros::LuaSandbox&)>& prepare = {}) {
  macros::DeckSession session;
  session.output_dir = output_dir;
  session.deck_path = deck;
  session.quiet = true;
  macros::LuaSandbox sandbox(TIREFE_LUA_DIR);
  macros::install_macros(sandbox, session);
  if (prepare) prepare(sandbox);
  InProcessRun run;
  try {
    sandbox.run_file(deck);
  } catch (const macros::DeckError& error) {
    run.error = error.what();
  }
  run.checks = static_cast<int>(session.checks.size());
  run.failed_checks = session.failed_checks();
  return run;
}

/// Runs a deck that must end without an error after 'checks' tirefe.check calls, all passed.
inline void check_deck_passes(const std::string& deck, const std::string& output_dir, int checks) {
  const InProcessRun run = run_deck_in_process(deck, output_dir);
  INFO(run.error);
  REQUIRE(run.error.empty());
  CHECK(run.checks == checks);
  CHECK(run.failed_checks == 0);
}

}  // namespace tirefe::testing
