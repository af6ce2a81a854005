// Interrupt: SIGINT and SIGTERM ask a run to stop after the step in progress, so that
// its result files close cleanly and it can say where it stopped. A host of the library
// asks the same of its calls with tirefe_cancel (include/tirefe.h).
#pragma once

#include <atomic>
#include <csignal>

namespace tirefe::macros {

/// Stands for tirefe_cancel where a signal number would (it is none).
constexpr int kHostCancel = -1;

/// The signal that asked the run to stop, kHostCancel, or 0.
inline std::atomic<int>& stop_signal() {
  static std::atomic<int> signal{0};
  return signal;
}

/// What asked the run to stop, for messages: "SIGINT", "SIGTERM" or "tirefe_cancel".
inline const char* stop_cause(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "tirefe_cancel";
}

/// SIGINT and SIGTERM ask the run to stop while this lives; the handlers it replaced come
/// back when it ends, so that a host process running decks (Python) keeps its own. No stop
/// is asked when it begins or after it ends: the next run starts afresh.
class StopHandlers {
 public:
  StopHandlers() {
    stop_signal().store(0);
    struct sigaction action {};
    action.sa_handler = [](int signal) { stop_signal().store(signal); };
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &replaced_[0]);
    sigaction(SIGTERM, &action, &replaced_[1]);
  }
  ~StopHandlers() {
    sigaction(SIGINT, &replaced_[0], nullptr);
    sigaction(SIGTERM, &replaced_[1], nullptr);
    stop_signal().store(0);
  }
  StopHandlers(const StopHandlers&) = delete;
  StopHandlers& operator=(const StopHandlers&) = delete;

 private:
  struct sigaction replaced_[2] = {};
};

}  // namespace tirefe::macros
