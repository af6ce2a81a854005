// BackgroundJob: one task at a time on a thread of its own (or, not threaded, run at once
// in the caller); a task's failure is rethrown to the thread that waits for it.
#pragma once

#include <chrono>
#include <functional>
#include <future>
#include <utility>

namespace tirefe::io {

class BackgroundJob {
 public:
  explicit BackgroundJob(bool threaded) : threaded_(threaded) {}
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;
  /// Waits for the task; its failure is dropped (wait for it first to hear of it).
  ~BackgroundJob() {
    if (job_.valid()) job_.wait();
  }

  /// Waits for the task before (rethrowing its failure), then starts 'task'.
  void start(std::function<void()> task) {
    wait();
    if (!threaded_) {
      task();
      return;
    }
    job_ = std::async(std::launch::async, std::move(task));
  }
  /// A task started and not finished.
  bool running() const { return job_.valid() && job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready; }
  /// Waits for the task started last, if any; rethrows its failure once.
  void wait() {
    if (!job_.valid()) return;
    std::future<void> job = std::move(job_);
    job.get();
  }

 private:
  bool threaded_;
  std::future<void> job_;
};

}  // namespace tirefe::io
