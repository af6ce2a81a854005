#include "deck/deck_model.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "deck/checkpoint.hpp"
#include "deck/deck_files.hpp"
#include "deck/interrupt.hpp"
#include "vehicle/tire_spindle.hpp"

namespace tirefe::macros {

namespace fs = std::filesystem;

DeckModel::DeckModel(std::string title, DeckSession& session)
    : title_(std::move(title)), session_(session), analysis_(model_), index_(++session.models_created) {
  if (session_.restart && session_.restart->model_index == index_) restart_ = session_.restart;
  session_.live_models.insert(this);
  load_functions_["ramp"] = Model::kRampLoadFunction;
  load_functions_["constant"] = model_.add_load_function(LoadFunction::constant(1.0));
  analysis_.add_step_observer([this](const Analysis& analysis, const StepRecord& record) {
    if (output_) output_->record(analysis.model(), analysis.state(), record);
    report_step(record);
    if (const int signal = stop_signal().load()) {
      // No flush here: the close that follows writes the rest without copying the file.
      throw std::runtime_error(std::string("stopped by ") + stop_cause(signal) + " after step " +
                               std::to_string(record.step) + " at t = " + std::to_string(record.time) +
                               (output_ ? "; '" + output_->path() + "' holds every completed step" : ""));
    }
  });
  analysis_.set_step_end_hook([this](Analysis&, const StepRecord& record) {
    if (checkpoint_file_.empty()) return;
    const bool by_steps = checkpoint_steps_ > 0 && record.step % checkpoint_steps_ == 0;
    const bool by_time = checkpoint_minutes_ > 0.0 && std::chrono::steady_clock::now() - last_checkpoint_ >=
                                                          std::chrono::duration<double>(60.0 * checkpoint_minutes_);
    if (by_steps || by_time) write_checkpoint(checkpoint_file_);
  });
}

DeckModel::~DeckModel() {
  session_.live_models.erase(this);
  // A model collected by Lua (the fit's evaluations) frees its file names for the next one.
  for (const std::string& purpose : {result_purpose(), xdmf_purpose(), checkpoint_purpose()})
    release_outputs(session_, purpose);
}

std::string DeckModel::result_purpose() const { return "the result file of " + described(); }
std::string DeckModel::checkpoint_purpose() const { return "the checkpoint of " + described(); }
std::string DeckModel::xdmf_purpose() const { return "the XDMF index of " + result_purpose(); }

std::string DeckModel::described() const { return "model " + std::to_string(index_) + " ('" + title_ + "')"; }

std::string DeckModel::checkpoint_path(const std::string& file) {
  return deck_output_path(session_, file, OutputFile::hdf5(checkpoint_purpose()));
}

void DeckModel::write_checkpoint(const std::string& file) {
  const std::string path = checkpoint_path(file);
  if (restart_) return;  // a restart has not reached its checkpoint yet: the file holds a later state
  if (analysis_.accepted_steps() == 0) throw ModelError("a checkpoint needs at least one solved step");
  if (!owned()) return;  // the owner writes it (after the same checks: every rank fails alike)
  Checkpoint checkpoint = capture_checkpoint(analysis_, output_.get(), index_, title_);
  checkpoint.parameters = session_.parameters;
  macros::write_checkpoint(path, checkpoint);
  last_checkpoint_ = std::chrono::steady_clock::now();
}

void DeckModel::schedule_checkpoints(const std::string& file, int steps, double minutes) {
  // Refused at the macro's line, not at the first step that writes it.
  const std::string path = checkpoint_path(file);
  checkpoint_file_ = file;
  if (owned()) remove_unfinished_checkpoint(path);  // a killed run's
  checkpoint_steps_ = steps;
  checkpoint_minutes_ = minutes;
  last_checkpoint_ = std::chrono::steady_clock::now();
}

void DeckModel::set_wheel_heading(int spindle, Heading heading) {
  for (const auto& [node, other] : wheel_headings_)
    if (other != heading)
      throw ModelError(std::string("this model's tires head ") + heading_name(other) +
                       ": give every tire heading = \"" + heading_name(other) +
                       "\" (one result file states one heading)");
  wheel_headings_[spindle] = heading;
}

void DeckModel::define_tire(const Tire& tire) { tires_[tire.name] = tire; }

const Tire& DeckModel::tire(const std::string& name) const {
  const auto found = tires_.find(name);
  if (found != tires_.end()) return found->second;
  std::string known;
  for (const auto& [other, unused] : tires_) known += (known.empty() ? "'" : ", '") + other + "'";
  throw ModelError("no tire named '" + name + "' in this model (" +
                   (known.empty() ? std::string("build one with model:tire first") : "it has " + known) + ")");
}

Heading DeckModel::wheel_heading(int node) const {
  const auto found = wheel_headings_.find(node);
  if (found == wheel_headings_.end())
    throw ModelError("node " + std::to_string(node + 1) + " is no tire's spindle: give node = tire.spindle");
  return found->second;
}

void DeckModel::require_state(const std::string& what) const {
  if (restart_ && skipped_steps_)
    throw ModelError(what + " needs the state at t = " + std::to_string(analysis_.state().time) +
                     ", which a restart skips (it continues from t = " + std::to_string(restart_->analysis.state.time) +
                     ")");
}

void DeckModel::load_checkpoint() {
  check_parameters(*restart_, session_.parameters);
  restore_checkpoint(*restart_, analysis_, output_.get());
  restart_.reset();
  session_.restart.reset();
  session_.progress.clear();
  if (!session_.quiet)
    std::printf("  restarted at step %d, t = %g\n", analysis_.accepted_steps(), analysis_.state().time);
}

void DeckModel::mark_advanced_elsewhere(const std::string& how) {
  stale_ = "model '" + title_ + "' was advanced on MPI rank " + std::to_string(session_.processes.owner(index_)) +
           " by " + how + "; read its results from the table " + how + " returns or from its result file";
}

DeckModel::Busy::Busy(DeckModel& deck, std::string what) : deck_(deck), outer_(std::move(deck.busy_with_)) {
  deck_.busy_with_ = std::move(what);
}

namespace {
/// Nodes and elements of a model.
std::pair<long long, long long> size_of(const Model& model) {
  long long elements = 0;
  for (const auto& block : model.blocks()) elements += block->size();
  return {model.mesh().node_count(), elements};
}
}  // namespace

bool DeckModel::fits() const {
  long long nodes = 0, elements = 0;
  for (const DeckModel* live : session_.live_models) {
    const auto [n, e] = size_of(live->model_);
    nodes += n;
    elements += e;
  }
  return nodes <= kMaxNodes && elements <= kMaxElements;
}

void DeckModel::check_size() const {
  if (fits()) return;
  const auto [nodes, elements] = size_of(model_);
  throw ModelError("model '" + title_ + "' has grown to " + std::to_string(nodes) + " nodes and " +
                   std::to_string(elements) + " elements; the models of a deck hold at most " +
                   std::to_string(kMaxNodes) + " nodes and " + std::to_string(kMaxElements) + " elements together (" +
                   std::to_string(session_.live_models.size()) + " models now)");
}

void DeckModel::define_section(const std::string& name, const BeamSection& section) {
  section.check();
  sections_[name] = section;
}

const BeamSection& DeckModel::section(const std::string& name) const {
  auto found = sections_.find(name);
  if (found == sections_.end())
    throw ModelError("no beam section named '" + name + "' (define it with model:section{...})");
  return found->second;
}

void DeckModel::define_surface(const std::string& name, std::shared_ptr<const RigidSurface> surface) {
  if (surfaces_.count(name)) throw ModelError("surface '" + name + "' is already defined");
  surfaces_[name] = std::move(surface);
}

std::shared_ptr<const RigidSurface> DeckModel::surface(const std::string& name) const {
  auto found = surfaces_.find(name);
  if (found != surfaces_.end()) return found->second;
  std::string known;
  for (const auto& entry : surfaces_) known += (known.empty() ? "" : ", ") + entry.first;
  throw ModelError("no surface named '" + name + "' (" +
                   (known.empty() ? "define one with model:surface{...}" : "defined: " + known) + ")");
}

TireSpindle* DeckModel::driven_spindle(int node) {
  auto found = spindles_.find(node);
  return found == spindles_.end() ? nullptr : found->second.get();
}

TireSpindle& DeckModel::drive_spindle(int node, SpinMode spin) {
  auto& spindle = spindles_[node];
  spindle = std::make_unique<TireSpindle>(analysis_, node, spin);
  return *spindle;
}

void DeckModel::define_load_function(const std::string& name, LoadFunction function) {
  if (load_functions_.count(name)) throw ModelError("load function '" + name + "' is already defined");
  load_functions_[name] = model_.add_load_function(std::move(function));
}

int DeckModel::load_function(const std::string& name) const {
  auto found = load_functions_.find(name);
  if (found == load_functions_.end()) {
    std::string known;
    for (const auto& entry : load_functions_) known += (known.empty() ? "" : ", ") + entry.first;
    throw ModelError("no load function named '" + name + "' (defined: " + known + ")");
  }
  return found->second;
}

void DeckModel::open_output(const std::string& file, int field_interval, double field_time_interval,
                            bool views_during_run) {
  if (output_) throw ModelError("this model already writes to '" + output_->path() + "'");
  const io::RunMetadata metadata{title_, session_.deck_path, session_.deck_text, session_.parameters,
                                 wheel_axes_statement()};
  // Every process claims the names, so that every rank refuses a clash alike.
  if (fs::path(file).extension() == ".xmf")
    throw ModelError("a result file named '" + file +
                     "' would be its own XDMF index (<name>.xmf is written beside it); give it the extension .h5");
  const std::string path = deck_output_path(session_, file, OutputFile::hdf5(result_purpose()));
  deck_output_path(session_, fs::path(file).replace_extension(".xmf").string(), OutputFile::xdmf(xdmf_purpose()));
  if (owned())
    output_ = std::make_unique<io::ResultFile>(path, metadata);
  else
    output_ = std::make_unique<io::ResultFile>(file, metadata, io::ResultStorage::Discarded);
  output_->set_field_interval(field_interval);
  output_->set_field_time_interval(field_time_interval);
  output_->set_views_during_run(views_during_run);
  for (const auto& describe : output_descriptions_) describe(*output_);
  output_descriptions_.clear();
}

void DeckModel::describe_output(std::function<void(io::ResultFile&)> describe) {
  if (output_)
    describe(*output_);
  else
    output_descriptions_.push_back(std::move(describe));
}

io::ResultFile& DeckModel::output_or_default() {
  if (!output_) {
    std::string stem = fs::path(session_.deck_path).stem().string();
    if (stem.empty()) stem = "tirefe";
    const int index = ++session_.default_outputs_opened;
    open_output(stem + (index > 1 ? "_" + std::to_string(index) : "") + ".h5", 0);
  }
  return *output_;
}

const std::vector<StepRecord>& DeckModel::advance(double duration) {
  output_or_default();
  if (!restart_) return analysis_.advance(duration);
  // Restarting: the deck runs again, its solves up to the checkpoint are skipped (only the
  // time moves on, by the arithmetic of a real step), and the checkpoint is loaded where
  // the original run wrote it: after the solve that ends on it, or before the one crossing it.
  State& state = analysis_.mutable_state();
  const double target = state.time + (duration > 0.0 ? duration : analysis_.time_step());
  const double checkpoint_time = restart_->analysis.state.time;
  const double round_off = 1e-12 * std::max(1.0, std::abs(target));
  if (target - round_off > checkpoint_time) {
    load_checkpoint();
    return analysis_.advance_to(target);
  }
  state.time = target;
  skipped_steps_ = true;
  if (checkpoint_time <= target + round_off) load_checkpoint();
  return no_records_;
}

void DeckModel::report_step(const StepRecord& record) const {
  session_.progress.record(record);
  if (!session_.verbose) return;
  std::printf("  step %5d  t = %-11.6g dt = %-10.4g newton %2d  |R| %.2e%s\n", record.step, record.time,
              record.step_size, record.newton_iterations, record.residual,
              record.cuts ? ("  (after " + std::to_string(record.cuts) + " cuts)").c_str() : "");
}

}  // namespace tirefe::macros
