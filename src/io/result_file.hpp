// ResultFile: one run's HDF5 output. Layout (docs/output.md):
//   /                 attributes: tirefe_version, git_commit, created, deck_path, units, title,
//                     axes (the spindle forces' axes and signs, as the deck gives them) and,
//                     with a tire, its heading ("+x" or "-x")
//   /deck             the deck's full text
//   /parameters       attributes: the deck's parameters after command-line overrides
//   /mesh/coordinates             node reference positions, nodes x 2 [m]
//   /mesh/blocks/<name>           element connectivity (0-based node indices), attribute "type"
//   /mesh/node_sets/<name>        0-based node indices
//   /mesh/cells, /mesh/cell_block the drawn blocks' cells in XDMF's mixed encoding, and each
//                                 cell's block
//   /history/<channel>            one row per accepted step: time, step_size, newton_iterations,
//                                 cuts, residual, augmentations, energies, and the deck's channels
//   /modes/<label>/frequency, rigid_body, shapes   modal analyses; a damped one adds
//                 damping_ratio, natural_frequency, shapes_imag (shapes holds the real part)
//   /fields/time, /fields/step    one row per field frame
//   /fields/displacement          frames x nodes x 3 (u_x, u_y, theta_z)
//   /fields/velocity              frames x nodes x 3 (dynamic runs)
//   /fields/deformation           frames x nodes x 3, models with a tire (below)
//   /surfaces/<name>/outline      frames x points x 2: a rigid surface where it is at the frame
//   /fields/frames/<k>/..., /surfaces/<name>/frames/<k>   frame k of the above as whole
//                                 datasets (virtual: no copies), for the XDMF index
// Contact rows are compressed, field rows not (docs/output.md). <stem>.xmf beside the file
// indexes the frames (io/xdmf.hpp). The file is published (Hdf5File::create_published):
// whole at every instant. Rows wait in memory and are flushed every quarter second of wall
// time (less often for a file so big that its flush, which copies it whole, takes over 12
// ms; sooner when the waiting rows reach half of what the file holds) and when the file
// closes, so a run that fails leaves a file readable up to its last step and a killed run
// one readable up to its last flush, some quarter second before the kill. A flush is
// written by a thread of its own while the run goes on (its rows were taken between two
// steps); the next flush, and anything else that writes to the file, waits for it. The
// index is rewritten (whole, by a rename) after a flush that brought frames: at every such
// flush while it is small, at most once a second beyond 1 MB, and at the close.
//
// Deformation: a tire's displacement with the rigid motion of its rim taken out. With X
// the reference position of a node, x = X + u, s the spindle and R = R(theta_s),
//     x_rigid = x_s + R (X - X_s)              where the rim's rigid motion puts the node,
//     e = x - x_rigid,   e_theta = theta - theta_s,
// in the fixed axes. A tire that rolls without deforming has e = 0, and x = x_rigid + e:
// the deformation rolls with the rim. Nodes of no tire: e = u.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <unordered_set>
#include <vector>

#include "core/model.hpp"
#include "core/state.hpp"
#include "core/step_record.hpp"
#include "io/background_job.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"

namespace tirefe::io {

/// Whether flushes may be written by a thread of their own: HDF5 built thread-safe (as
/// Debian's is) serialises its calls; otherwise they are written by the run's thread.
#ifdef H5_HAVE_THREADSAFE
inline constexpr bool kHdf5Threadsafe = true;
#else
inline constexpr bool kHdf5Threadsafe = false;
#endif

/// Where a result file goes: to disk, or nowhere (an MPI rank that does not own the
/// model: its writes land in memory and are dropped, and it records no steps).
enum class ResultStorage { File, Discarded };

struct RunMetadata {
  std::string title;
  std::string deck_path;
  std::string deck_text;
  std::vector<std::pair<std::string, std::string>> parameters;  // the deck's parameters, as text
  std::string axes{};  // the axes and signs of the spindle forces; none when empty
};

/// A name that becomes part of a path in the result file (a history channel, a surface, a
/// node set, a contact block, a modal label): IoError, at the macro that gives it, unless
/// it is non-empty, without '/' and not '.' or '..'. 'what' says whose it is ("surface name").
void require_path_name(const std::string& name, const std::string& what);

/// A modal analysis's result as /modes/<label> holds it: frequencies, rigid-body flags and
/// shapes (dof_count x modes; the real part of complex ones); a damped one adds its spin
/// rate, damping ratios, natural frequencies and the shapes' imaginary part.
struct ModeTable {
  double time = 0.0;  // of the state the modes linearise about [s]
  std::vector<double> frequencies_hz;
  std::vector<bool> rigid_body;
  Eigen::MatrixXd shapes;
  bool damped = false;
  double spin_rate = 0.0;
  std::vector<double> damping_ratios, natural_frequencies_hz;
  Eigen::MatrixXd shapes_imag;
};

class ResultFile {
 public:
  /// A history channel's value at an accepted step, from the committed state and the step's record.
  using Channel = std::function<double(const State&, const StepRecord&)>;

  ResultFile(const std::string& path, const RunMetadata& metadata, ResultStorage storage = ResultStorage::File);
  /// Closes the file, with the index of every frame beside it.
  ~ResultFile();
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;
  const std::string& path() const { return file_.path(); }
  bool discarded() const { return discarded_; }
  /// The file, once a flush being written is done.
  Hdf5File& file() {
    flush_job_.wait();
    return file_;
  }

  /// Adds a history channel (one value per accepted step). A channel added after steps were
  /// recorded holds NaN for those earlier steps.
  void add_channel(const std::string& name, const std::string& unit, Channel channel);
  /// Writes displacement (and velocity) fields every 'interval' accepted steps (0: never).
  void set_field_interval(int interval) { field_interval_ = interval; }
  /// Writes fields at the first accepted step at or after every multiple of 'interval'
  /// seconds (0: never), whatever the step sizes.
  void set_field_time_interval(double interval) { field_time_interval_ = interval; }

  /// Whether the run makes the views of its frames (the XDMF index's datasets) as it writes
  /// them, or leaves them to `tirefe --views FILE` (make_frame_views): some 50 us of the
  /// writer's time per view, five per frame of a tire on a drum.
  void set_views_during_run(bool during_run) { views_during_run_ = during_run; }

  /// A tire's rim: its spindle node and the nodes the tire carries (for /fields/deformation).
  /// Rims and node sets given after the mesh was written are ignored.
  void add_rim(int spindle, std::vector<int> nodes);
  /// Shows a node set as points of their own in the XDMF index (a tread layer's contact nodes).
  void show_node_set(const std::string& name);
  /// A surface's points at 'time', the same number every time; an unbounded surface (a road)
  /// drawn to 'reach' beyond 'centre'.
  using Outline = std::function<std::vector<Eigen::Vector2d>(double time, const Eigen::Vector2d& centre, double reach)>;
  /// Draws a rigid surface at every field frame: a polyline through the outline's points
  /// (closed: back to the first). Frames written before it are drawn too, at their times.
  void add_surface(const std::string& name, bool closed, Outline outline);
  /// After a restart refilled the rows: the views and the index of the frames it brought back.
  void index_restored_frames();

  /// The values history channel 'name' recorded, one per accepted step (none before the
  /// first step): what the file will hold, flushed or not.
  std::vector<double> history_values(const std::string& name);
  /// Records one accepted step (writes the mesh first if it has not been written).
  void record(const Model& model, const State& state, const StepRecord& record);
  /// Writes the result of a modal analysis of 'model' under /modes/<label>.
  void write_modes(const std::string& label, const Model& model, const ModeTable& modes);
  /// Writes a field frame now, whatever the interval.
  void write_fields(const Model& model, const State& state, int step);
  int steps_recorded() const { return steps_recorded_; }
  /// Writes the mesh and opens the history datasets now (a restart refills them).
  void start(const Model& model);
  /// A restart's count of the rows refilled from its checkpoint.
  void set_steps_recorded(int steps) { steps_recorded_ = steps; }
  /// Flushes and waits for the flush to be written.
  void flush();
  /// Starts a flush, written by a thread of its own while the run goes on, if a quarter
  /// second of wall time has passed since the last flush (and twenty times that flush's own
  /// time), or if the rows waiting in memory reach half the file's rows (and at least
  /// kFlushBytes): what a kill can lose is bounded, what flushing costs too. A flush that
  /// failed throws here, at the next step.
  void flush_if_due();
  /// The wall time between flushes while rows arrive.
  static constexpr std::chrono::milliseconds kFlushInterval{250};
  /// The least bytes of waiting rows that call for a flush before its time.
  static constexpr size_t kFlushBytes = 256 * 1024;
  /// Frames recorded whose views the writer has not been given yet: what a close would
  /// still write (at most kMaxUnviewedFrames - 1 after a step).
  size_t frames_awaiting_views() const;
  /// The least frames whose views are written between flushes, together.
  static constexpr size_t kViewBatch = 16;
  /// The most history channels of a result file (docs/decks.md, Limits).
  static constexpr size_t kMaxChannels = 10000;
  /// The most frames whose views wait to be written (a few tenths of a second of the writer's work).
  static constexpr size_t kMaxUnviewedFrames = 256;
  /// The bytes of waiting rows that are written between flushes (the copy waits for the
  /// flush): memory holds about this much, whatever the file's size.
  static constexpr size_t kRowBatchBytes = 1024 * 1024;

 private:
  /// Bytes of the rows waiting in memory for the next flush.
  size_t pending_bytes() const;
  /// Takes the rows and frames waiting and starts writing them (after the last flush).
  void start_flush();
  /// The flush's writing, on the writer's thread: the views of the frames first_view ..
  /// last_view - 1, the rows, the file's copy, then 'frames' (their times) in the index.
  void write_flush(size_t first_view, size_t last_view, const std::vector<double>& frames);
  /// Starts writing the views of the frames without them, if kViewBatch or more wait, and
  /// the rows waiting, if kRowBatchBytes or more: no flush is due, so the file's copy and
  /// the index wait for the next flush.
  void start_writes_if_due();
  struct HistoryChannel {
    ExtendibleDataset* dataset;
    Channel value;
  };
  struct Rim {
    int spindle;
    std::vector<int> nodes;
  };
  struct Surface {
    std::string name;
    Outline outline;
    ExtendibleDataset* rows;
  };
  void write_mesh(const Model& model);
  void add_mesh_grids(const Model& model);
  XdmfGrid node_grid(const std::string& name, const std::string& topology, long long cells, int nodes_per_cell,
                     const XdmfData& connectivity) const;
  void append_deformation(const Model& model, const State& state);
  void append_outline(Surface& surface, double time);
  void write_views(size_t frame);
  /// The views of the frames that have none yet (made together: HDF5's code and its
  /// metadata stay in the processor's caches).
  void write_unviewed_views();
  /// The first frame without views: every frame in the index has them, and the frames_viewed_ first.
  size_t first_unviewed_frame() const { return std::max(frames_viewed_, index_.frames()); }
  void write_index();
  /// <stem>.xmf beside the file.
  std::string index_path() const;
  void write_index_if_due();
  /// Adds the frames the last flush put in the file to the index.
  void index_flushed_frames();
  size_t frames_written() const { return index_.frames() + unflushed_frames_.size(); }
  double frame_time(size_t frame) const;
  /// Shapes as modes x (3 nodes), like the displacement fields.
  void write_shape_table(const std::string& path, const Model& model, const Eigen::MatrixXd& shapes);
  void start_history();
  /// With frames by time: the first step at or after the next multiple of the interval.
  void schedule_next_frame(double frame_time);

  Hdf5File file_;
  bool discarded_;
  std::vector<std::pair<std::string, std::string>> channel_names_;  // name, unit
  std::unordered_set<std::string> channel_set_;                     // their names
  std::vector<Channel> pending_channels_;
  std::vector<HistoryChannel> channels_;
  bool mesh_written_ = false;
  bool views_during_run_ = true;
  int field_interval_ = 0;
  double field_time_interval_ = 0.0;
  double next_field_time_ = -std::numeric_limits<double>::infinity();
  int steps_recorded_ = 0;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::duration last_flush_cost_{};
  size_t flushed_bytes_ = 0;    // bytes of rows written by the flushes so far
  size_t unflushed_bytes_ = 0;  // bytes of rows written since the last flush, not yet copied
  ExtendibleDataset* field_time_ = nullptr;
  ExtendibleDataset* field_step_ = nullptr;
  ExtendibleDataset* field_displacement_ = nullptr;
  ExtendibleDataset* field_velocity_ = nullptr;
  ExtendibleDataset* field_deformation_ = nullptr;  // with a rim
  std::vector<Rim> rims_;
  std::vector<std::string> shown_node_sets_;
  std::vector<Surface> surfaces_;
  std::vector<double> row_;                                // one frame's deformation
  Eigen::Vector2d view_centre_ = Eigen::Vector2d::Zero();  // where the last frame's structure is
  double view_reach_ = 1.0;
  XdmfIndex index_;                       // the frames the file on disk holds
  std::vector<double> unflushed_frames_;  // the times of frames written since the last flush
  size_t frames_indexed_ = 0;             // in the index file
  size_t frames_viewed_ = 0;              // the frames whose views are written or being written
  std::chrono::steady_clock::time_point last_index_write_ = std::chrono::steady_clock::now();
  // Last, so that it is destroyed first: the flush it writes uses the members above.
  BackgroundJob flush_job_{kHdf5Threadsafe};
};

}  // namespace tirefe::io
