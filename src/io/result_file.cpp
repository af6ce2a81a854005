#include "io/result_file.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ctime>
#include <limits>

#include "tirefe/version.hpp"

namespace tirefe::io {

namespace {
std::string utc_now() {
  char text[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}
}  // namespace

ResultFile::ResultFile(const std::string& path, const RunMetadata& metadata, ResultStorage storage)
    : file_(storage == ResultStorage::File ? Hdf5File::create(path) : Hdf5File::create_in_memory(path)),
      discarded_(storage == ResultStorage::Discarded) {
  file_.write_attribute("/", "tirefe_version", std::string(kVersion));
  file_.write_attribute("/", "git_commit", std::string(kGitCommit));
  file_.write_attribute("/", "created", utc_now());
  file_.write_attribute("/", "title", metadata.title);
  file_.write_attribute("/", "deck_path", metadata.deck_path);
  file_.write_attribute("/", "units", std::string("SI: m, N, s, rad, kg, Pa"));
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
  add_channel("time", "s", [](const Analysis&, const StepRecord& step) { return step.time; });
  add_channel("step_size", "s", [](const Analysis&, const StepRecord& step) { return step.step_size; });
  add_channel("newton_iterations", "", [](const Analysis&, const StepRecord& step) {
    return static_cast<double>(step.newton_iterations);
  });
  add_channel("cuts", "", [](const Analysis&, const StepRecord& step) { return static_cast<double>(step.cuts); });
  add_channel("residual", "N", [](const Analysis&, const StepRecord& step) { return step.residual; });
  add_channel("augmentations", "", [](const Analysis&, const StepRecord& step) {
    return static_cast<double>(step.augmentations);
  });
  add_channel("energy_kinetic", "J", [](const Analysis&, const StepRecord& step) { return step.energy.kinetic; });
  add_channel("energy_strain", "J", [](const Analysis&, const StepRecord& step) { return step.energy.strain; });
  add_channel("external_work", "J", [](const Analysis&, const StepRecord& step) { return step.energy.external_work; });
  add_channel("energy_dissipated", "J", [](const Analysis&, const StepRecord& step) { return step.energy.dissipated; });
  file_.flush();
}

ResultFile::~ResultFile() {
  if (field_index_.frame_times.empty()) return;
  try {
    write_field_index();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "tirefe: warning: %s\n", error.what());
  }
}

void ResultFile::write_field_index() const {
  std::filesystem::path index(path());
  index.replace_extension(".xmf");
  write_xdmf(index.string(), field_index_);
}

void ResultFile::add_channel(const std::string& name, const std::string& unit, Channel channel) {
  for (const auto& existing : channel_names_)
    if (existing.first == name) throw IoError("history channel '" + name + "' is defined twice");
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

void ResultFile::start_history() {
  for (size_t i = 0; i < channel_names_.size(); ++i) {
    ExtendibleDataset& dataset =
        file_.create_extendible("/history/" + channel_names_[i].first, {}, channel_names_[i].second);
    channels_.push_back({&dataset, std::move(pending_channels_[i])});
  }
  pending_channels_.clear();
}

void ResultFile::write_mesh(const Model& model) {
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
    field_index_.blocks.push_back({block->name(), block->size(), per_element});
  }
  field_index_.hdf5_file_name = std::filesystem::path(file_.path()).filename().string();
  field_index_.nodes = mesh.node_count();
  for (const auto& [name, nodes] : mesh.node_sets())
    file_.write_int_vector("/mesh/node_sets/" + name, std::vector<long long>(nodes.begin(), nodes.end()));
  const std::vector<hsize_t> node_field{static_cast<hsize_t>(mesh.node_count()), 3};
  field_time_ = &file_.create_extendible("/fields/time", {}, "s");
  field_step_ = &file_.create_extendible("/fields/step", {});
  field_displacement_ = &file_.create_extendible("/fields/displacement", node_field, "m, m, rad");
  field_velocity_ = &file_.create_extendible("/fields/velocity", node_field, "m/s, m/s, rad/s");
  mesh_written_ = true;
}

void ResultFile::write_modes(const std::string& label, const Analysis& analysis, const ModalResult& modes) {
  if (discarded_) return;
  write_mode_group(label, analysis, modes.frequencies_hz, modes.rigid_body, modes.shapes);
  flush();
}

void ResultFile::write_modes(const std::string& label, const Analysis& analysis, const DampedModalResult& modes) {
  if (discarded_) return;
  const std::string group =
      write_mode_group(label, analysis, modes.frequencies_hz, modes.rigid_body, modes.shapes.real());
  file_.write_attribute(group, "spin_rate", modes.spin_rate);
  file_.write_vector(group + "/damping_ratio", modes.damping_ratios);
  file_.write_vector(group + "/natural_frequency", modes.natural_frequencies_hz);
  write_shape_table(group + "/shapes_imag", analysis, modes.shapes.imag());
  flush();
}

std::string ResultFile::write_mode_group(const std::string& label, const Analysis& analysis,
                                         const std::vector<double>& frequencies_hz, const std::vector<bool>& rigid_body,
                                         const Eigen::MatrixXd& shapes) {
  if (!mesh_written_) write_mesh(analysis.model());
  const std::string group = "/modes/" + label;
  file_.write_attribute(group, "time", analysis.state().time);
  file_.write_vector(group + "/frequency", frequencies_hz);
  file_.write_int_vector(group + "/rigid_body", std::vector<long long>(rigid_body.begin(), rigid_body.end()));
  write_shape_table(group + "/shapes", analysis, shapes);
  return group;
}

void ResultFile::write_shape_table(const std::string& path, const Analysis& analysis, const Eigen::MatrixXd& shapes) {
  const int nodes = analysis.model().mesh().node_count();
  std::vector<double> values(static_cast<size_t>(shapes.cols()) * nodes * kDofsPerNode);
  for (Eigen::Index mode = 0; mode < shapes.cols(); ++mode)
    for (int dof = 0; dof < nodes * kDofsPerNode; ++dof) values[mode * nodes * kDofsPerNode + dof] = shapes(dof, mode);
  Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> table(
      values.data(), shapes.cols(), nodes * kDofsPerNode);
  file_.write_matrix(path, table);
  file_.write_attribute(path, "layout", std::string("modes x (3 nodes): u_x, u_y, theta_z per node"));
}

void ResultFile::write_fields(const Analysis& analysis, int step) {
  if (discarded_) return;
  if (!mesh_written_) write_mesh(analysis.model());
  const State& state = analysis.state();
  if (state.displacement.size() != static_cast<Eigen::Index>(field_displacement_->row_size()))
    throw IoError("the mesh changed after output started; fields cannot be written to '" + path() + "'");
  field_time_->append(state.time);
  field_index_.frame_times.push_back(state.time);
  field_step_->append(static_cast<double>(step));
  field_displacement_->append(state.displacement.data());
  field_velocity_->append(state.velocity.data());
  flush();
}

void ResultFile::start(const Analysis& analysis) {
  if (discarded_) return;
  if (!mesh_written_) write_mesh(analysis.model());
  if (channels_.empty()) start_history();
}

void ResultFile::record(const Analysis& analysis, const StepRecord& record) {
  if (discarded_) {  // the model's owner records the step; the channels are not evaluated here
    ++steps_recorded_;
    return;
  }
  start(analysis);
  for (auto& channel : channels_) channel.dataset->append(channel.value(analysis, record));
  ++steps_recorded_;
  const bool frame_due = (field_interval_ > 0 && record.step % field_interval_ == 0) ||
                         (field_time_interval_ > 0.0 && record.time >= next_field_time_);
  if (frame_due) {
    write_fields(analysis, record.step);  // flushes
    if (field_time_interval_ > 0.0) {
      // The next multiple of the interval after this frame (a tiny margin absorbs round-off in t).
      const double margin = 1e-9 * field_time_interval_;
      next_field_time_ = (std::floor((record.time + margin) / field_time_interval_) + 1.0) * field_time_interval_ - margin;
    }
  }
  else
    flush_if_due();
}

void ResultFile::flush_if_due() {
  // Flushing costs tens of microseconds; a quarter second of wall time between flushes
  // bounds what a killed run can lose without slowing short steps down.
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ < std::chrono::milliseconds(250)) return;
  file_.flush();
  last_flush_ = now;
}

void ResultFile::flush() {
  file_.flush();
  last_flush_ = std::chrono::steady_clock::now();
}

}  // namespace tirefe::io
