// ResultFile: one run's HDF5 output. Layout (docs/output.md):
//   /                 attributes: tirefe_version, git_commit, created, deck_path, units, title
//   /deck             the deck's full text
//   /parameters       attributes: the deck's parameters after command-line overrides
//   /mesh/coordinates             node reference positions, nodes x 2 [m]
//   /mesh/blocks/<name>           element connectivity (0-based node indices), attribute "type"
//   /mesh/node_sets/<name>        0-based node indices
//   /history/<channel>            one row per accepted step: time, step_size, newton_iterations,
//                                 cuts, residual, augmentations, energies, and the deck's channels
//   /modes/<label>/frequency, rigid_body, shapes   modal analyses; a damped one adds
//                 damping_ratio, natural_frequency, shapes_imag (shapes holds the real part)
//   /fields/time, /fields/step    one row per field frame
//   /fields/displacement          frames x nodes x 3 (u_x, u_y, theta_z)
//   /fields/velocity              frames x nodes x 3 (dynamic runs)
// <stem>.xmf beside the file indexes the fields for ParaView (io/xdmf.hpp).
// Rows are flushed at field frames and at least every quarter second of wall time, and
// when the file closes, so a run that fails leaves a file readable up to its last step
// and a killed run one readable up to its last flush.
#pragma once

#include <chrono>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"
#include "solvers/analysis.hpp"
#include "solvers/modal.hpp"

namespace tirefe::io {

/// Where a result file goes: to disk, or nowhere (an MPI rank that does not own the
/// model: its writes land in memory and are dropped, and it records no steps).
enum class ResultStorage { File, Discarded };

struct RunMetadata {
  std::string title;
  std::string deck_path;
  std::string deck_text;
  std::vector<std::pair<std::string, std::string>> parameters;  // the deck's parameters, as text
};

class ResultFile {
 public:
  using Channel = std::function<double(const Analysis&, const StepRecord&)>;

  ResultFile(const std::string& path, const RunMetadata& metadata, ResultStorage storage = ResultStorage::File);
  /// Closes the file, and writes the XDMF index of its fields beside it (<stem>.xmf).
  ~ResultFile();
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;
  const std::string& path() const { return file_.path(); }
  bool discarded() const { return discarded_; }
  Hdf5File& file() { return file_; }

  /// Adds a history channel (one value per accepted step). A channel added after steps were
  /// recorded holds NaN for those earlier steps.
  void add_channel(const std::string& name, const std::string& unit, Channel channel);
  /// Writes displacement (and velocity) fields every 'interval' accepted steps (0: never).
  void set_field_interval(int interval) { field_interval_ = interval; }
  /// Writes fields at the first accepted step at or after every multiple of 'interval'
  /// seconds (0: never), whatever the step sizes.
  void set_field_time_interval(double interval) { field_time_interval_ = interval; }
  int field_interval() const { return field_interval_; }

  /// Records one accepted step (writes the mesh first if it has not been written).
  void record(const Analysis& analysis, const StepRecord& record);
  /// Writes the result of a modal analysis under /modes/<label>.
  void write_modes(const std::string& label, const Analysis& analysis, const ModalResult& modes);
  void write_modes(const std::string& label, const Analysis& analysis, const DampedModalResult& modes);
  /// Writes a field frame now, whatever the interval.
  void write_fields(const Analysis& analysis, int step);
  int steps_recorded() const { return steps_recorded_; }
  /// Writes the mesh and opens the history datasets now (a restart refills them).
  void start(const Analysis& analysis);
  /// A restart's count of the rows refilled from its checkpoint.
  void set_steps_recorded(int steps) { steps_recorded_ = steps; }
  void flush();

 private:
  struct HistoryChannel {
    ExtendibleDataset* dataset;
    Channel value;
  };
  void write_mesh(const Model& model);
  /// The common part of write_modes: time, frequencies, flags and the shapes' real part.
  std::string write_mode_group(const std::string& label, const Analysis& analysis,
                               const std::vector<double>& frequencies_hz, const std::vector<bool>& rigid_body,
                               const Eigen::MatrixXd& shapes);
  /// Shapes as modes x (3 nodes), like the displacement fields.
  void write_shape_table(const std::string& path, const Analysis& analysis, const Eigen::MatrixXd& shapes);
  void write_field_index() const;
  void start_history();
  void flush_if_due();

  Hdf5File file_;
  bool discarded_;
  std::vector<std::pair<std::string, std::string>> channel_names_;  // name, unit
  std::vector<Channel> pending_channels_;
  std::vector<HistoryChannel> channels_;
  bool mesh_written_ = false;
  int field_interval_ = 0;
  double field_time_interval_ = 0.0;
  double next_field_time_ = -std::numeric_limits<double>::infinity();
  int steps_recorded_ = 0;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
  ExtendibleDataset* field_time_ = nullptr;
  ExtendibleDataset* field_step_ = nullptr;
  ExtendibleDataset* field_displacement_ = nullptr;
  ExtendibleDataset* field_velocity_ = nullptr;
  XdmfFields field_index_;  // what the XDMF file points at
};

}  // namespace tirefe::io
