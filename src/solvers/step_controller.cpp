#include "solvers/step_controller.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/mesh.hpp"

namespace tirefe {

void StepController::set_windows(std::vector<StepWindow> windows) {
  for (const StepWindow& window : windows)
    if (!(window.to > window.from) || !(window.step > 0.0))
      throw ModelError("a step window needs from < to and a positive step");
  std::sort(windows.begin(), windows.end(), [](const StepWindow& a, const StepWindow& b) { return a.from < b.from; });
  windows_ = std::move(windows);
}

const std::vector<StepRecord>& StepController::advance_to(SteppedSystem& system, double target) {
  records_.clear();
  for (const StepWindow& window : windows_) {
    const double from = std::clamp(window.from, system.time(), target), to = std::clamp(window.to, from, target);
    if (from > system.time()) advance_span(system, from);
    if (to > system.time()) {
      const StepSizes outside = sizes_;
      sizes_ = {window.step, window.step};
      advance_span(system, to);
      sizes_ = outside;
    }
  }
  advance_span(system, target);
  return records_;
}

void StepController::advance_span(SteppedSystem& system, double target) {
  const size_t first = records_.size();
  const double duration = target - system.time();
  const double time_round_off = 1e-12 * std::max(1.0, std::abs(target));
  double step = std::min(sizes_.current, control_.max_step > 0.0 ? control_.max_step : sizes_.current);
  records_.reserve(first + static_cast<size_t>(std::min(std::max(duration, 0.0) / step, 1e6)) + 16);
  while (system.time() < target - time_round_off) {
    const double remaining = target - system.time();
    // Take the rest in one step if a sliver would be left over; it ends on the target exactly.
    const bool last = step >= remaining || remaining - step < 1e-6 * step;
    step = last ? remaining : step;
    // No step is cut below the nominal one halved 'depth' (2 max_cuts) times: otherwise a
    // run that scrapes through with tiny steps, failing again after each, lets the step
    // dwindle from cut to cut without ever stopping.
    const int depth = control_.depth > 0 ? control_.depth : 2 * control_.max_cuts;
    const double smallest = std::max(control_.min_step, std::ldexp(std::min(sizes_.nominal, remaining), -depth));
    StepRecord record;
    while (!system.try_step(step, last && record.cuts == 0 ? target : system.time() + step, record)) {
      ++record.cuts;
      const double cut = 0.5 * step;
      if (record.cuts > control_.max_cuts || cut < smallest * (1.0 - 1e-9))
        throw StepFailure(system.failure_message(record.cuts - 1, step));
      step = cut;
    }
    system.commit_step(step, record);
    records_.push_back(record);
    // Grow back toward the nominal step after an easy convergence (before the observers,
    // so that a checkpoint taken by one holds the next step's size).
    if (record.newton_iterations <= control_.easy_iterations) step = std::min(sizes_.nominal, step * control_.growth);
    sizes_.current = step;
    notify(record);
    if (system.time() < target - time_round_off)
      check_step_budget(system, static_cast<int>(records_.size() - first), duration / sizes_.nominal, record.step_size);
  }
}

std::string SteppedSystem::where() const {
  std::ostringstream text;
  text << "at t = " << time();
  return text.str();
}

void StepController::notify(const StepRecord& record) const {
  for (const Observer& observer : observers_) observer(record);
  if (closing_observer_) closing_observer_(record);
}

void StepController::check_step_budget(const SteppedSystem& system, int steps_taken, double nominal_steps,
                                       double step) const {
  if (control_.step_budget <= 0) return;
  const double allowed = control_.step_budget * (std::ceil(nominal_steps - 1e-9) + 1.0);
  if (steps_taken < allowed) return;
  std::ostringstream message;
  message << "the step budget ran out " << system.where() << ": " << steps_taken
          << " steps where dt = " << sizes_.nominal << " asks for " << std::ceil(nominal_steps - 1e-9)
          << " (the last dt = " << step
          << "); steps that converge only far below dt point to a model out of balance or too light "
          << "(a tiny rotary inertia). Check the loads, supports and masses, or raise "
          << "model:step_control{ step_budget = " << control_.step_budget << " }";
  throw StepFailure(message.str());
}

}  // namespace tirefe
