// Checkpoints (docs/restart.md): the complete state of one model's run between two
// steps, in an HDF5 file of its own:
//   /                   attributes: format, title, model_index, node_count, time, steps
//   /analysis/*         u, v, a, the forces and reactions of the last step, step size,
//                       energy bookkeeping and the integrator (CarriedState)
//   /blocks/<i>         every element block's committed history as bytes, with the
//                       block's name, kernel type and history size as attributes
//   /parameters         the deck's parameters (names, values as text), which a restart
//                       must repeat
//   /rows/<i>           every row the result file held (its history, fields and
//                       contact datasets), so that a restarted run writes a complete file
// A restart rebuilds the model with the deck, checks that it is the same model (nodes,
// blocks, integrator) and loads this state into it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/result_file.hpp"
#include "solvers/analysis.hpp"

namespace tirefe::macros {

struct SavedBlock {
  std::string name, kernel_type;
  long long bytes_per_element = 0, elements = 0;
  std::vector<unsigned char> history;
};

struct SavedRows {
  std::string path;                  // the dataset in the result file
  std::vector<long long> row_shape;  // empty for scalar rows
  long long rows = 0;
  std::vector<double> values;
};

struct Checkpoint {
  std::string title;
  int model_index = 0;  // which tirefe.model{} of the deck, counted from 1
  int node_count = 0;
  CarriedState analysis;
  std::vector<SavedBlock> blocks;
  bool has_output = false;
  int steps_recorded = 0;
  std::vector<SavedRows> rows;
  /// The deck's tirefe.parameters after command-line overrides (name, value as text).
  std::vector<std::pair<std::string, std::string>> parameters;
};

/// The state of 'analysis' and the rows of 'output' (may be null) now.
Checkpoint capture_checkpoint(Analysis& analysis, io::ResultFile* output, int model_index, const std::string& title);
/// Loads a checkpoint into a model built by the same deck; throws ModelError naming what differs.
void restore_checkpoint(const Checkpoint& checkpoint, Analysis& analysis, io::ResultFile* output);

/// Throws ModelError listing every parameter whose value differs from the checkpoint's:
/// a restart continues the same case, so that the result file's /parameters stay true.
void check_parameters(const Checkpoint& checkpoint, const std::vector<std::pair<std::string, std::string>>& parameters);

/// Writes beside 'path' first and renames, so a run killed meanwhile keeps the last checkpoint whole.
void write_checkpoint(const std::string& path, const Checkpoint& checkpoint);
/// Removes what a run killed while writing the checkpoint 'path' left beside it.
void remove_unfinished_checkpoint(const std::string& path);
/// Throws io::IoError for a missing, unreadable or incomplete checkpoint file.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace tirefe::macros
