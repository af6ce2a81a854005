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

inline void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = [](int signal) { stop_signal().store(signal); };
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace tirefe::macros
