#include "io/result_file.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ctime>
#include <limits>

#include "io/frame_views.hpp"
#include "io/temporary_file.hpp"
#include "tirefe/version.hpp"

namespace tirefe::io {

namespace {
std::string utc_now() {
  char text[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}
/// <stem>.xmf beside the result file 'path'.
std::string index_path_of(const std::string& path) {
  return std::filesystem::path(path).replace_extension(".xmf").string();
}

/// The result file, its index's temporary refused now if anything is in its way, not at the first frame.
Hdf5File create_published_with_index(const std::string& path) {
  clear_for_temporary(index_path_of(path) + ".partial", kXdmfSignature);
  return Hdf5File::create_published(path);
}
}  // namespace

void require_path_name(const std::string& name, const std::string& what) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    throw IoError(what + " '" + name +
                  "' must be a non-empty name without '/', not '.' or '..' (use '_', e.g. 'tip_x')");
}

ResultFile::ResultFile(const std::string& path, const RunMetadata& metadata, ResultStorage storage)
    : file_(storage == ResultStorage::File ? create_published_with_index(path) : Hdf5File::create_in_memory(path)),
      discarded_(storage == ResultStorage::Discarded),
      index_(std::filesystem::path(path).filename().string()) {
  file_.write_attribute("/", "tirefe_version", std::string(kVersion));
  file_.write_attribute("/", "git_commit", std::string(kGitCommit));
  file_.write_attribute("/", "created", utc_now());
  file_.write_attribute("/", "title", metadata.title);
  file_.write_attribute("/", "deck_path", metadata.deck_path);
  file_.write_attribute("/", "units", std::string("SI: m, N, s, rad, kg, Pa"));
  if (!metadata.axes.empty()) file_.write_attribute("/", "axes", metadata.axes);  // "heading" with a tire
  file_.write_string_dataset("/deck", metadata.deck_text);
  // Numbers as numbers (post-processing reads the drum size or the speed from here).
  for (const auto& [name, text] : metadata.parameters) {
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    if (!text.empty() && end && *end == '\0')
      file_.write_attribute("/parameters", name, number);
    else
      file_.write_attribute("/parameters", name, text);
  }
  // The built-in step channels come first in every history.
  add_channel("time", "s", [](const State&, const StepRecord& step) { return step.time; });
  add_channel("step_size", "s", [](const State&, const StepRecord& step) { return step.step_size; });
  add_channel("newton_iterations", "",
              [](const State&, const StepRecord& step) { return static_cast<double>(step.newton_iterations); });
  add_channel("cuts", "", [](const State&, const StepRecord& step) { return static_cast<double>(step.cuts); });
  add_channel("residual", "N", [](const State&, const StepRecord& step) { return step.residual; });
  add_channel("augmentations", "",
              [](const State&, const StepRecord& step) { return static_cast<double>(step.augmentations); });
  add_channel("energy_kinetic", "J", [](const State&, const StepRecord& step) { return step.energy.kinetic; });
  add_channel("energy_strain", "J", [](const State&, const StepRecord& step) { return step.energy.strain; });
  add_channel("external_work", "J", [](const State&, const StepRecord& step) { return step.energy.external_work; });
  add_channel("energy_dissipated", "J", [](const State&, const StepRecord& step) { return step.energy.dissipated; });
  add_channel("surface_work", "J", [](const State&, const StepRecord& step) { return step.energy.surface_work; });
  add_channel("unstored_work", "J", [](const State&, const StepRecord& step) { return step.energy.unstored_work; });
  add_channel("energy_damping", "J", [](const State&, const StepRecord& step) { return step.energy.damping; });
  add_channel("contact_dissipated", "J",
              [](const State&, const StepRecord& step) { return step.energy.contact_dissipated; });
  add_channel("energy_balance_error", "J",
              [](const State&, const StepRecord& step) { return step.energy.balance_error; });
  file_.flush();
}

ResultFile::~ResultFile() {
  try {
    flush_job_.wait();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "tirefe: warning: %s\n", error.what());
  }
  if (file_.failed()) return;  // reported; the file on disk keeps its last flush
  try {
    file_.stage();
    write_unviewed_views();
    file_.close();
    index_flushed_frames();
    if (frames_indexed_ != index_.frames()) write_index();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "tirefe: warning: %s\n", error.what());
  }
}

std::string ResultFile::index_path() const { return index_path_of(path()); }

void ResultFile::write_index() {
  if (index_.empty()) return;
  try {
    index_.write(index_path());
  } catch (const IoError&) {
    file_.abandon();
    throw;
  }
  frames_indexed_ = index_.frames();
  last_index_write_ = std::chrono::steady_clock::now();
}

void ResultFile::index_flushed_frames() {
  for (double time : unflushed_frames_) index_.add_frame(time);
  unflushed_frames_.clear();
}

double ResultFile::frame_time(size_t frame) const {
  return frame < index_.frames() ? index_.times()[frame] : unflushed_frames_[frame - index_.frames()];
}

void ResultFile::write_index_if_due() {
  // Rewriting the whole index after every frame costs the square of the frame count in
  // all: a long run's index (beyond 1 MB, some 200 frames of a tire on a drum) is
  // rewritten once a second at most.
  const auto now = std::chrono::steady_clock::now();
  if (index_.size() > (1u << 20) && now - last_index_write_ < std::chrono::seconds(1)) return;
  write_index();
}

void ResultFile::add_channel(const std::string& name, const std::string& unit, Channel channel) {
  flush_job_.wait();
  // Checked here, at the macro that names the channel: HDF5 would take a '/' for a group
  // path and fail (or nest the channel) only when the first step writes it.
  require_path_name(name, "history channel name");
  if (channel_set_.count(name)) throw IoError("history channel '" + name + "' is defined twice");
  // Each channel is a dataset of its own (some 26 kB of memory): more than this is a
  // loop gone wrong, refused before it costs gigabytes.
  if (channel_names_.size() >= kMaxChannels)
    throw IoError("history channel '" + name + "' would be channel " + std::to_string(kMaxChannels + 1) +
                  "; a result file holds at most " + std::to_string(kMaxChannels) + " history channels");
  channel_set_.insert(name);
  channel_names_.emplace_back(name, unit);
  if (channels_.empty()) {
    pending_channels_.push_back(std::move(channel));
    return;
  }
  // A channel defined mid-run (a contact added after inflation) has no value for the
  // steps before it existed: those rows hold NaN, so every channel keeps one row per step.
  ExtendibleDataset& dataset = file_.create_extendible("/history/" + name, {}, unit);
  for (int row = 0; row < steps_recorded_; ++row) dataset.append(std::numeric_limits<double>::quiet_NaN());
  channels_.push_back({&dataset, std::move(channel)});
}

std::vector<double> ResultFile::history_values(const std::string& name) {
  if (discarded_) throw IoError("the history of '" + path() + "' is not kept by this process");
  flush_job_.wait();
  std::string names;
  for (size_t i = 0; i < channel_names_.size(); ++i) {
    if (channel_names_[i].first == name)
      return channels_.empty() ? std::vector<double>{} : file_.read_rows(*channels_[i].dataset);
    names += (i == 0 ? "" : ", ") + channel_names_[i].first;
  }
  throw IoError("no history channel '" + name + "' in '" + path() + "': its channels are " + names);
}

void ResultFile::start_history() {
  flush_job_.wait();
  for (size_t i = 0; i < channel_names_.size(); ++i) {
    ExtendibleDataset& dataset =
        file_.create_extendible("/history/" + channel_names_[i].first, {}, channel_names_[i].second);
    channels_.push_back({&dataset, std::move(pending_channels_[i])});
  }
  pending_channels_.clear();
}

void ResultFile::write_mesh(const Model& model) {
  flush_job_.wait();
  const Mesh& mesh = model.mesh();
  Eigen::MatrixXd coordinates(mesh.node_count(), 2);
  for (int node = 0; node < mesh.node_count(); ++node) coordinates.row(node) = mesh.position(node).transpose();
  file_.write_matrix("/mesh/coordinates", coordinates);
  file_.write_attribute("/mesh", "node_numbering", std::string("0-based (deck node n is row n-1)"));
  for (const auto& block : model.blocks()) {
    const int per_element = block->nodes_per_element();
    std::vector<long long> connectivity;
    connectivity.reserve(static_cast<size_t>(block->size()) * per_element);
    for (int e = 0; e < block->size(); ++e)
      for (int node : block->element_nodes(e)) connectivity.push_back(node);
    const std::string path = "/mesh/blocks/" + block->name();
    file_.write_int_matrix(path, block->size(), per_element, connectivity.data());
  }
  for (const auto& [name, nodes] : mesh.node_sets())
    file_.write_int_vector("/mesh/node_sets/" + name, std::vector<long long>(nodes.begin(), nodes.end()));
  const std::vector<hsize_t> node_field{static_cast<hsize_t>(mesh.node_count()), 3};
  field_time_ = &file_.create_extendible("/fields/time", {}, "s");
  field_step_ = &file_.create_extendible("/fields/step", {});
  // Not compressed: a moving tire's doubles shrink by a fifth at most, for half of what a
  // flush costs (docs/output.md).
  field_displacement_ = &file_.create_extendible("/fields/displacement", node_field, "m, m, rad");
  field_velocity_ = &file_.create_extendible("/fields/velocity", node_field, "m/s, m/s, rad/s");
  if (!rims_.empty()) {
    field_deformation_ = &file_.create_extendible("/fields/deformation", node_field, "m, m, rad");
    file_.write_attribute("/fields/deformation", "meaning",
                          std::string("displacement less the rigid motion of the tire's rim, fixed axes"));
  }
  add_mesh_grids(model);
  mesh_written_ = true;
}

XdmfGrid ResultFile::node_grid(const std::string& name, const std::string& topology, long long cells,
                               int nodes_per_cell, const XdmfData& connectivity) const {
  const long long nodes = static_cast<long long>(field_displacement_->row_size() / 3);
  XdmfGrid grid{name, topology, cells, nodes_per_cell, connectivity, {"/mesh/coordinates", {nodes, 2}}, {}};
  auto field = [&](const char* field_name, const char* type) {
    const bool vector = std::string(type) == "Vector";
    grid.attributes.push_back({field_name,
                               type,
                               "Node",
                               {std::string("/fields/frames/{frame}/") + field_name,
                                vector ? std::vector<long long>{nodes, 3} : std::vector<long long>{nodes}}});
  };
  field("displacement", "Vector");
  field("velocity", "Vector");
  field("rotation", "Scalar");
  if (field_deformation_) field("deformation", "Vector");
  return grid;
}

void ResultFile::add_mesh_grids(const Model& model) {
  // The blocks of lines, triangles and quadrilaterals in one mixed topology (each cell: its
  // XDMF type code, for a polyline its node count, its nodes), a block repeating another's
  // connectivity (the pressure on the tread) once; point-like blocks as grids of their own.
  std::vector<long long> cells, cell_block;
  std::vector<std::vector<int>> drawn;
  std::string block_names;
  std::vector<XdmfGrid> point_grids;
  for (const auto& block : model.blocks()) {
    const int per_element = block->nodes_per_element();
    if (block->size() == 0) continue;
    if (per_element == 1) {
      point_grids.push_back(node_grid(block->name(), "Polyvertex", block->size(), 1,
                                      {"/mesh/blocks/" + block->name(), {block->size(), 1}, true}));
      continue;
    }
    const int code = per_element == 2 ? 0x2 : per_element == 3 ? 0x4 : per_element == 4 ? 0x5 : 0;
    if (code == 0) continue;  // no XDMF cell of that many nodes
    std::vector<int> connectivity;
    for (int e = 0; e < block->size(); ++e)
      for (int node : block->element_nodes(e)) connectivity.push_back(node);
    if (std::find(drawn.begin(), drawn.end(), connectivity) != drawn.end()) continue;
    for (int e = 0; e < block->size(); ++e) {
      cells.push_back(code);
      if (per_element == 2) cells.push_back(2);
      for (int node : block->element_nodes(e)) cells.push_back(node);
      cell_block.push_back(static_cast<long long>(drawn.size()));
    }
    block_names += (drawn.empty() ? "" : ", ") + block->name();
    drawn.push_back(std::move(connectivity));
  }
  if (!cells.empty()) {
    file_.write_int_vector("/mesh/cells", cells);
    file_.write_attribute("/mesh/cells", "encoding",
                          std::string("XDMF mixed topology: per cell its type code (2 polyline, 4 triangle, "
                                      "5 quadrilateral), for a polyline its node count, its nodes"));
    file_.write_int_vector("/mesh/cell_block", cell_block);
    file_.write_attribute("/mesh/cell_block", "blocks", block_names);
    const long long count = static_cast<long long>(cell_block.size());
    XdmfGrid mesh = node_grid("mesh", "Mixed", count, 0, {"/mesh/cells", {static_cast<long long>(cells.size())}, true});
    mesh.attributes.push_back({"block", "Scalar", "Cell", {"/mesh/cell_block", {count}, true}});
    index_.add_grid(mesh);
  }
  for (const XdmfGrid& grid : point_grids) index_.add_grid(grid);
  for (const std::string& name : shown_node_sets_) {
    const auto& sets = model.mesh().node_sets();
    const auto found = sets.find(name);
    if (found == sets.end() || found->second.empty()) continue;
    const long long size = static_cast<long long>(found->second.size());
    index_.add_grid(node_grid(name, "Polyvertex", size, 1, {"/mesh/node_sets/" + name, {size}, true}));
  }
}

void ResultFile::add_rim(int spindle, std::vector<int> nodes) {
  if (discarded_ || mesh_written_) return;
  rims_.push_back({spindle, std::move(nodes)});
}

void ResultFile::show_node_set(const std::string& name) {
  if (discarded_ || mesh_written_) return;
  shown_node_sets_.push_back(name);
}

void ResultFile::add_surface(const std::string& name, bool closed, Outline outline) {
  if (discarded_) return;
  flush_job_.wait();
  for (const Surface& surface : surfaces_)
    if (surface.name == name) throw IoError("surface '" + name + "' is drawn twice in '" + path() + "'");
  const std::vector<Eigen::Vector2d> points = outline(0.0, view_centre_, view_reach_);
  const long long count = static_cast<long long>(points.size());
  if (count < 2) throw IoError("surface '" + name + "' has fewer than two points to draw");
  const std::string group = "/surfaces/" + name;
  Surface& surface = surfaces_.emplace_back(Surface{
      name, std::move(outline), &file_.create_extendible(group + "/outline", {static_cast<hsize_t>(count), 2}, "m")});
  // Segments from each point to the next (and from the last back to the first).
  std::vector<long long> segments;
  for (long long i = 0; i + 1 < count + (closed ? 1 : 0); ++i) {
    segments.push_back(i);
    segments.push_back((i + 1) % count);
  }
  const long long segment_count = static_cast<long long>(segments.size() / 2);
  file_.write_int_matrix(group + "/segments", segment_count, 2, segments.data());
  // clang-format off
  XdmfGrid grid{name, "Polyline", segment_count, 2, {group + "/segments", {segment_count, 2}, true},
                {group + "/frames/{frame}", {count, 2}}, {}};
  // clang-format on
  // The frames written before the surface existed show it where its motion put it then
  // (the frames without views yet get theirs with the others).
  const size_t earlier = frames_written();
  for (size_t frame = 0; frame < earlier; ++frame) {
    append_outline(surface, frame_time(frame));
    if (frame < first_unviewed_frame() && views_during_run_) {
      const RowView view = surface_view(name, frame);
      file_.write_row_view(view.path, *surface.rows, frame, view.first, view.count, view.width);
    }
  }
  index_.add_grid(grid);
  if (earlier > 0) {
    flush();
    write_index();
  }
}

void ResultFile::append_outline(Surface& surface, double time) {
  const std::vector<Eigen::Vector2d> points = surface.outline(time, view_centre_, view_reach_);
  if (points.size() * 2 != surface.rows->row_size())
    throw IoError("surface '" + surface.name + "' changed its number of points");
  row_.resize(points.size() * 2);
  for (size_t i = 0; i < points.size(); ++i) {
    row_[2 * i] = points[i].x();
    row_[2 * i + 1] = points[i].y();
  }
  surface.rows->append(row_.data());
}

void ResultFile::append_deformation(const Model& model, const State& state) {
  const Mesh& mesh = model.mesh();
  const Eigen::VectorXd& u = state.displacement;
  row_.assign(u.data(), u.data() + u.size());  // nodes of no tire: e = u
  for (const Rim& rim : rims_) {
    const Eigen::Vector2d spindle_reference = mesh.position(rim.spindle);
    const Eigen::Vector2d spindle = spindle_reference + u.segment<2>(dof_index(rim.spindle, kUx));
    const double spin = u[dof_index(rim.spindle, kRz)];
    const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(spin).toRotationMatrix();
    std::fill_n(row_.begin() + dof_index(rim.spindle, kUx), kDofsPerNode, 0.0);
    for (int node : rim.nodes) {
      const Eigen::Vector2d reference = mesh.position(node);
      const Eigen::Vector2d position = reference + u.segment<2>(dof_index(node, kUx));
      const Eigen::Vector2d e = position - spindle - rotation * (reference - spindle_reference);
      const int first = dof_index(node, kUx);
      row_[first] = e.x();
      row_[first + 1] = e.y();
      row_[first + 2] = u[dof_index(node, kRz)] - spin;
    }
  }
  field_deformation_->append(row_.data());
}

void ResultFile::write_views(size_t frame) {
  if (!views_during_run_) return;
  std::vector<std::string> surfaces;
  for (const Surface& surface : surfaces_) surfaces.push_back(surface.name);
  const auto has = [this](const std::string& dataset) { return file_.find_extendible(dataset) != nullptr; };
  for (const RowView& view : frame_views(frame, has, surfaces))
    file_.write_row_view(view.path, *file_.find_extendible(view.source), frame, view.first, view.count, view.width);
}

void ResultFile::write_unviewed_views() {
  for (size_t frame = first_unviewed_frame(); frame < frames_written(); ++frame) write_views(frame);
  frames_viewed_ = frames_written();
}

void ResultFile::index_restored_frames() {
  if (discarded_ || !mesh_written_) return;
  flush_job_.wait();
  const std::vector<double> times = file_.read_doubles("/fields/time");
  for (size_t frame = frames_written(); frame < times.size(); ++frame) unflushed_frames_.push_back(times[frame]);
  // The frames go on where the interrupted run's would have, not at the first step.
  if (!times.empty()) schedule_next_frame(times.back());
  flush();
  write_index();
}

void ResultFile::write_modes(const std::string& label, const Model& model, const ModeTable& modes) {
  if (discarded_) return;
  flush_job_.wait();
  if (!mesh_written_) write_mesh(model);
  const std::string group = "/modes/" + label;
  file_.write_attribute(group, "time", modes.time);
  file_.write_vector(group + "/frequency", modes.frequencies_hz);
  file_.write_int_vector(group + "/rigid_body",
                         std::vector<long long>(modes.rigid_body.begin(), modes.rigid_body.end()));
  write_shape_table(group + "/shapes", model, modes.shapes);
  if (modes.damped) {
    file_.write_attribute(group, "spin_rate", modes.spin_rate);
    file_.write_vector(group + "/damping_ratio", modes.damping_ratios);
    file_.write_vector(group + "/natural_frequency", modes.natural_frequencies_hz);
    write_shape_table(group + "/shapes_imag", model, modes.shapes_imag);
  }
  flush();
}

void ResultFile::write_shape_table(const std::string& path, const Model& model, const Eigen::MatrixXd& shapes) {
  const int nodes = model.mesh().node_count();
  std::vector<double> values(static_cast<size_t>(shapes.cols()) * nodes * kDofsPerNode);
  for (Eigen::Index mode = 0; mode < shapes.cols(); ++mode)
    for (int dof = 0; dof < nodes * kDofsPerNode; ++dof) values[mode * nodes * kDofsPerNode + dof] = shapes(dof, mode);
  Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> table(
      values.data(), shapes.cols(), nodes * kDofsPerNode);
  file_.write_matrix(path, table);
  file_.write_attribute(path, "layout", std::string("modes x (3 nodes): u_x, u_y, theta_z per node"));
}

void ResultFile::write_fields(const Model& model, const State& state, int step) {
  if (discarded_) return;
  if (!mesh_written_) write_mesh(model);
  if (state.displacement.size() != static_cast<Eigen::Index>(field_displacement_->row_size()))
    throw IoError("the mesh changed after output started; fields cannot be written to '" + path() + "'");
  // Where the structure is: a road is drawn a structure's size beyond it (at least a metre).
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (int node = 0; node < model.mesh().node_count(); ++node) {
    const Eigen::Vector2d position = model.mesh().position(node) + state.displacement.segment<2>(dof_index(node, kUx));
    low = low.cwiseMin(position);
    high = high.cwiseMax(position);
  }
  if (model.mesh().node_count() > 0) {
    view_centre_ = 0.5 * (low + high);
    view_reach_ = std::max((high - low).norm(), 1.0);
  }
  field_time_->append(state.time);
  field_step_->append(static_cast<double>(step));
  field_displacement_->append(state.displacement.data());
  field_velocity_->append(state.velocity.data());
  if (field_deformation_) append_deformation(model, state);
  for (Surface& surface : surfaces_) append_outline(surface, state.time);
  unflushed_frames_.push_back(state.time);
  flush_if_due();
}

void ResultFile::start(const Model& model) {
  if (discarded_) return;
  if (!mesh_written_) write_mesh(model);
  if (channels_.empty()) start_history();
}

void ResultFile::record(const Model& model, const State& state, const StepRecord& record) {
  if (discarded_) {  // the model's owner records the step; the channels are not evaluated here
    ++steps_recorded_;
    return;
  }
  start(model);
  for (auto& channel : channels_) channel.dataset->append(channel.value(state, record));
  ++steps_recorded_;
  const bool frame_due = (field_interval_ > 0 && record.step % field_interval_ == 0) ||
                         (field_time_interval_ > 0.0 && record.time >= next_field_time_);
  if (frame_due) {
    write_fields(model, state, record.step);
    schedule_next_frame(record.time);
  }
  flush_if_due();
}

void ResultFile::schedule_next_frame(double frame_time) {
  if (field_time_interval_ <= 0.0) return;
  // The next multiple of the interval after this frame (a tiny margin absorbs round-off in t).
  const double margin = 1e-9 * field_time_interval_;
  next_field_time_ = (std::floor((frame_time + margin) / field_time_interval_) + 1.0) * field_time_interval_ - margin;
}

size_t ResultFile::pending_bytes() const {
  size_t bytes = 0;
  for (const ExtendibleDataset& dataset : file_.extendible_datasets()) bytes += dataset.pending_bytes();
  return bytes;
}

void ResultFile::flush_if_due() {
  // A flush writes the rows waiting in memory and copies the whole file (a millisecond per
  // few MB): every quarter second of wall time, field frames or not, and never before
  // twenty times the last flush's own time has passed: flushing takes at most some 5% of
  // the run. A fast run also flushes when its waiting rows reach half of what the file
  // holds: the file grows geometrically between copies, so that the copies cost at most
  // about three times the file, and a disk filling up still finds the last copy holding
  // most of the rows (the copy needs room beside the file being written). While a flush is
  // being written, the rows wait for the next; rows that have grown so wait for it, so that
  // a run faster than its disk holds no more than that in memory. Frames whose views lag
  // kMaxUnviewedFrames behind make the run wait for the writer too: a flush, and the close
  // of a run stopped by a signal, then has that many views at most to write.
  const bool grown = pending_bytes() + unflushed_bytes_ >= std::max(kFlushBytes, flushed_bytes_ / 2);
  const bool views_behind = frames_awaiting_views() >= kMaxUnviewedFrames;
  if (!grown && !views_behind && flush_job_.running()) return;
  flush_job_.wait();  // a finished flush's failure fails the step that finds it
  const auto since = std::chrono::steady_clock::now() - last_flush_;
  if (!grown && (since < kFlushInterval || since < 20 * last_flush_cost_)) {
    start_writes_if_due();
    return;
  }
  start_flush();
}

size_t ResultFile::frames_awaiting_views() const {
  const size_t frames = field_time_ ? static_cast<size_t>(field_time_->rows()) : 0;  // this thread's count
  return frames - std::min(frames, frames_viewed_);
}

void ResultFile::start_writes_if_due() {
  // The views are most of a flush's work: made while the writer would idle, a few dozen at
  // a time, they do not pile up for the flushes, whose spacing grows with the file, nor for
  // the end of the run, which waits for them. The rows, written as they reach a batch, do
  // not pile up in memory: buffers of a batch's size are reused, not grown and faulted in.
  const size_t from = first_unviewed_frame(), to = frames_written();
  const bool rows_due = pending_bytes() >= kRowBatchBytes;
  if (to - from < kViewBatch && !rows_due) return;
  frames_viewed_ = to;
  if (rows_due) {
    unflushed_bytes_ += pending_bytes();
    file_.stage();
  }
  flush_job_.start([this, from, to, rows_due] {
    silence_hdf5_errors();
    for (size_t frame = from; frame < to; ++frame) write_views(frame);
    if (rows_due) file_.write_staged();
  });
}

void ResultFile::flush() {
  start_flush();
  flush_job_.wait();
}

void ResultFile::start_flush() {
  flush_job_.wait();
  // Taken between steps: the rows appended so far and the frames among them. The run goes
  // on appending to buffers of its own while the flush writes these.
  const size_t first_view = first_unviewed_frame();
  frames_viewed_ = frames_written();
  std::vector<double> frames;
  frames.swap(unflushed_frames_);
  flushed_bytes_ += pending_bytes() + unflushed_bytes_;
  unflushed_bytes_ = 0;
  file_.stage();
  flush_job_.start([this, first_view, last_view = frames_viewed_, frames = std::move(frames)] {
    write_flush(first_view, last_view, frames);
  });
}

void ResultFile::write_flush(size_t first_view, size_t last_view, const std::vector<double>& frames) {
  silence_hdf5_errors();  // the writer's own thread: failures are thrown, not printed
  // The views are the frames' own cost: not the flush's time, which spaces the flushes.
  for (size_t frame = first_view; frame < last_view; ++frame) write_views(frame);
  const auto start = std::chrono::steady_clock::now();
  file_.flush_staged();
  last_flush_ = std::chrono::steady_clock::now();
  last_flush_cost_ = last_flush_ - start;
  if (frames.empty()) return;
  // After the flush: the index names only what the file holds.
  for (double time : frames) index_.add_frame(time);
  write_index_if_due();
}

}  // namespace tirefe::io
