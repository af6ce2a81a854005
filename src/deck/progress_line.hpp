// ProgressLine: how far a run has got, on one terminal line rewritten in place ('\r') at
// most a few times a second: simulated time, accepted steps, step cuts, the wall time
// spent and, once the deck has said when it ends (tirefe.progress{ end_time = T }), an
// estimate of the wall time left. It draws only on a terminal: a log gets nothing.
#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string>

namespace tirefe {
struct StepRecord;
}

namespace tirefe::macros {

class ProgressLine {
 public:
  using Clock = std::chrono::steady_clock;

  /// 'stream' if it is a terminal, else nullptr.
  static std::FILE* terminal(std::FILE* stream);
  /// The line for a state; 'remaining' wall seconds when they can be estimated.
  static std::string text(double time, std::optional<double> end_time, int steps, int cuts, double elapsed,
                          std::optional<double> remaining);

  /// Draws on 'stream' from now on (nullptr: never, the default), at most every 'interval'.
  void draw_on(std::FILE* stream, Clock::duration interval = std::chrono::milliseconds(250));
  /// The simulated time the deck ends at: the estimate of the wall time left needs it.
  void set_end_time(double end_time);
  /// An accepted step of any of the deck's models (tires may step on their own threads).
  void record(const StepRecord& record);
  /// Erases the line so that other output starts on a clean one; the next step redraws it.
  void clear();
  /// Standard output for logs written during steps (Newton, fits): erases the line first.
  std::ostream& output() { return output_; }

 private:
  // Unbuffered: every write clears the line, then goes to stdout (in order with printf).
  struct ClearingBuffer : std::streambuf {
    explicit ClearingBuffer(ProgressLine& owner) : line(owner) {}
    int overflow(int c) override;
    std::streamsize xsputn(const char* text, std::streamsize count) override;
    ProgressLine& line;
  };

  void draw(Clock::time_point now);

  std::mutex mutex_;
  std::FILE* stream_ = nullptr;
  Clock::duration interval_{};
  Clock::time_point start_ = Clock::now();
  std::optional<Clock::time_point> last_draw_;
  bool drawn_ = false;
  std::optional<double> end_time_;
  // The first step seen and the latest state: the rate of simulated time per wall second.
  std::optional<std::pair<double, Clock::time_point>> first_;
  double time_ = 0.0;
  int steps_ = 0, cuts_ = 0;
  ClearingBuffer buffer_{*this};
  std::ostream output_{&buffer_};
};

}  // namespace tirefe::macros
