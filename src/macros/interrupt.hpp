// Interrupt: SIGINT and SIGTERM ask a run to stop after the step in progress, so that
// its result files close cleanly and it can say where it stopped.
#pragma once

#include <atomic>
#include <csignal>

namespace tirefe::macros {

/// The signal that asked the run to stop, or 0.
inline std::atomic<int>& stop_signal() {
  static std::atomic<int> signal{0};
  return signal;
}

inline void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = [](int signal) { stop_signal().store(signal); };
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace tirefe::macros
