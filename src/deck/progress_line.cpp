#include "deck/progress_line.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "solvers/analysis.hpp"

namespace tirefe::macros {

namespace {

/// "m:ss", or "h:mm:ss" from an hour on.
std::string clock_text(double seconds) {
  const long total = std::lround(std::max(seconds, 0.0));
  char text[32];
  if (total >= 3600)
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  else
    std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  return text;
}

}  // namespace

std::FILE* ProgressLine::terminal(std::FILE* stream) { return stream && isatty(fileno(stream)) ? stream : nullptr; }

std::string ProgressLine::text(double time, std::optional<double> end_time, int steps, int cuts, double elapsed,
                               std::optional<double> remaining) {
  char line[160];
  int length = std::snprintf(line, sizeof line, "t = %.4g s", time);
  if (end_time) length += std::snprintf(line + length, sizeof line - length, " of %.4g s", *end_time);
  length += std::snprintf(line + length, sizeof line - length, "  step %d  cuts %d  elapsed %s", steps, cuts,
                          clock_text(elapsed).c_str());
  if (remaining) std::snprintf(line + length, sizeof line - length, "  left ~%s", clock_text(*remaining).c_str());
  return line;
}

void ProgressLine::draw_on(std::FILE* stream, Clock::duration interval) {
  std::lock_guard<std::mutex> lock(mutex_);
  stream_ = stream;
  interval_ = interval;
}

void ProgressLine::set_end_time(double end_time) {
  std::lock_guard<std::mutex> lock(mutex_);
  end_time_ = end_time;
}

void ProgressLine::record(const StepRecord& record) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!stream_) return;
  const Clock::time_point now = Clock::now();
  if (!first_) first_ = std::make_pair(record.time, now);
  time_ = std::max(time_, record.time);
  steps_ = std::max(steps_, record.step);  // the models of a vehicle step together
  cuts_ += record.cuts;
  if (!last_draw_ || now - *last_draw_ >= interval_) draw(now);
}

void ProgressLine::draw(Clock::time_point now) {
  const auto seconds = [](Clock::duration span) { return std::chrono::duration<double>(span).count(); };
  std::optional<double> remaining;
  const double simulated = time_ - first_->first, spent = seconds(now - first_->second);
  if (end_time_ && simulated > 0.0 && spent > 0.0) remaining = (*end_time_ - time_) * spent / simulated;
  std::fflush(stdout);  // the deck's own output first, above the line
  // The cursor is left at the start: output that does not clear the line overwrites it.
  const std::string line = text(time_, end_time_, steps_, cuts_, seconds(now - start_), remaining);
  std::fprintf(stream_, "\r%s\x1b[K\r", line.c_str());
  std::fflush(stream_);
  drawn_ = true;
  last_draw_ = now;
}

void ProgressLine::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!drawn_) return;
  std::fputs("\r\x1b[K", stream_);
  std::fflush(stream_);
  drawn_ = false;
}

int ProgressLine::ClearingBuffer::overflow(int c) {
  if (c == traits_type::eof()) return traits_type::not_eof(c);
  line.clear();
  return std::fputc(c, stdout);
}

std::streamsize ProgressLine::ClearingBuffer::xsputn(const char* text, std::streamsize count) {
  line.clear();
  return static_cast<std::streamsize>(std::fwrite(text, 1, static_cast<size_t>(count), stdout));
}

}  // namespace tirefe::macros
