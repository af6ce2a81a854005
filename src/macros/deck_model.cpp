#include "macros/deck_model.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "macros/interrupt.hpp"

namespace tirefe::macros {

namespace fs = std::filesystem;

DeckModel::DeckModel(std::string title, DeckSession& session)
    : title_(std::move(title)), session_(session), analysis_(model_) {
  load_functions_["ramp"] = Model::kRampLoadFunction;
  load_functions_["constant"] = model_.add_load_function(LoadFunction::constant(1.0));
  analysis_.add_step_observer([this](const Analysis& analysis, const StepRecord& record) {
    if (output_) output_->record(analysis, record);
    print_step(record);
    if (const int signal = stop_signal().load()) {
      if (output_) output_->flush();
      throw std::runtime_error(std::string("stopped by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
                               " after step " + std::to_string(record.step) + " at t = " +
                               std::to_string(record.time) +
                               (output_ ? "; '" + output_->path() + "' holds every completed step" : ""));
    }
  });
}

void DeckModel::define_section(const std::string& name, const BeamSection& section) {
  section.check();
  sections_[name] = section;
}

const BeamSection& DeckModel::section(const std::string& name) const {
  auto found = sections_.find(name);
  if (found == sections_.end()) throw ModelError("no beam section named '" + name + "' (define it with model:section{...})");
  return found->second;
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

void DeckModel::open_output(const std::string& file, int field_interval, double field_time_interval) {
  if (output_) throw ModelError("this model already writes to '" + output_->path() + "'");
  fs::path path(file);
  if (path.is_relative()) path = fs::path(session_.output_dir) / path;
  std::error_code ignored;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ignored);
  output_ = std::make_unique<io::ResultFile>(path.string(),
                                             io::RunMetadata{title_, session_.deck_path, session_.deck_text, session_.parameters});
  output_->set_field_interval(field_interval);
  output_->set_field_time_interval(field_time_interval);
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
  return analysis_.advance(duration);
}

void DeckModel::print_step(const StepRecord& record) const {
  if (session_.quiet) return;
  std::printf("  step %5d  t = %-11.6g dt = %-10.4g newton %2d  |R| %.2e%s\n", record.step, record.time,
              record.step_size, record.newton_iterations, record.residual,
              record.cuts ? ("  (after " + std::to_string(record.cuts) + " cuts)").c_str() : "");
}

}  // namespace tirefe::macros
