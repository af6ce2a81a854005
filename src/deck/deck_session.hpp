// DeckSession: what one `tirefe deck.lua` run shares across the deck's models: where
// output goes, the tally of the deck's self-checks, and the processes that run the deck
// together (one, or the ranks of an MPI run: docs/vehicle.md).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "deck/progress_line.hpp"

namespace tirefe {
class TireExchange;
class TireSpindle;
}  // namespace tirefe
namespace tirefe::macros {

struct Checkpoint;
class DeckModel;

struct CheckResult {
  std::string name;
  bool passed;
};

/// The processes that run one deck together, each the whole deck. Every process computes
/// every model; model k (counted from 1 in creation order) is owned by process
/// (k - 1) mod count, which alone writes its result file and solves it in a vehicle.
struct DeckProcesses {
  int rank = 0;
  int count = 1;
  int owner(int model_index) const { return (model_index - 1) % count; }
  bool owns(int model_index) const { return owner(model_index) == rank; }
};

/// Makes the exchange a vehicle asks its tires through; owners[i] is the process of tire i.
using TireExchangeFactory = std::function<std::unique_ptr<TireExchange>(std::vector<TireSpindle*> tires,
                                                                        std::vector<int> owners, bool threads)>;

struct DeckSession {
  std::string output_dir = "results";
  std::string deck_path;
  /// Folders the command line lets the deck read or write besides its own (--allow-read,
  /// --allow-write; docs/security.md).
  std::vector<std::string> read_folders, write_folders;
  /// Every file the run writes, by resolved path: what it is (one file, one purpose).
  std::map<std::string, std::string> output_purposes;
  std::string deck_text;
  bool quiet = false;
  bool verbose = false;  // one line per accepted step on standard output
  /// The in-place progress line (drawn on a terminal only); output during a run clears it first.
  ProgressLine progress;
  std::vector<CheckResult> checks;
  // The deck's tirefe.parameters{...} after command-line overrides, as text, for the
  // result file's /parameters (a run's file says which case it is).
  std::vector<std::pair<std::string, std::string>> parameters;
  int default_outputs_opened = 0;
  int models_created = 0;
  /// The models alive now (made, not yet collected): their size is bounded together.
  std::set<const DeckModel*> live_models;
  /// --restart: the checkpoint a model continues from (docs/restart.md); cleared once loaded.
  std::shared_ptr<const Checkpoint> restart;
  DeckProcesses processes;
  /// Unset: a TireGroup in this process (threads). An MPI run installs its own.
  TireExchangeFactory tire_exchange;

  int failed_checks() const {
    int failed = 0;
    for (const auto& check : checks) failed += check.passed ? 0 : 1;
    return failed;
  }
};

}  // namespace tirefe::macros
