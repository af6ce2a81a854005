// DeckSession: what one `tirefe deck.lua` run shares across the deck's models: where
// output goes, and the tally of the deck's self-checks.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tirefe::io {
struct Checkpoint;
}

namespace tirefe::macros {

struct CheckResult {
  std::string name;
  bool passed;
};

struct DeckSession {
  std::string output_dir = "results";
  std::string deck_path;
  std::string deck_text;
  bool quiet = false;
  std::vector<CheckResult> checks;
  // The deck's tirefe.parameters{...} after command-line overrides, as text, for the
  // result file's /parameters (a run's file says which case it is).
  std::vector<std::pair<std::string, std::string>> parameters;
  int default_outputs_opened = 0;
  int models_created = 0;
  /// --restart: the checkpoint a model continues from (docs/restart.md); cleared once loaded.
  std::shared_ptr<const io::Checkpoint> restart;

  int failed_checks() const {
    int failed = 0;
    for (const auto& check : checks) failed += check.passed ? 0 : 1;
    return failed;
  }
};

}  // namespace tirefe::macros
