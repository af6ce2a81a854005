#include "vehicle/tire_group.hpp"

#include <algorithm>

namespace tirefe {

namespace {
// A round follows the last within tens of microseconds (the vehicle's corrector and the
// commits' output in between): a lane that waits spins about that long before it sleeps,
// as a wake-up costs as much. Only while the lanes have a core each: spinning threads
// that share cores take them from the lanes with work.
constexpr int kSpins = 4000;
inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}
}  // namespace

TireGroup::TireGroup(std::vector<TireSpindle*> tires, bool concurrent, int lanes)
    : TireExchange(std::move(tires)), commands_(size()) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  lanes_ = concurrent ? std::clamp(lanes > 0 ? lanes : cores, 1, std::max(1, size())) : 1;
  concurrent_ = lanes_ > 1;
  spins_ = lanes_ <= cores ? kSpins : 0;
  workers_.reserve(lanes_ - 1);
  for (int lane = 1; lane < lanes_; ++lane) workers_.emplace_back([this] { work(); });
}

TireGroup::~TireGroup() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void TireGroup::take_tires() {
  for (int tire; (tire = next_tire_.fetch_add(1)) < size();) {
    if (task_ == Task::Serve)
      (*replies_)[tire] = spindle(tire).serve((*requests_)[tire]);  // serve() never throws
    else
      spindle(tire).prepare_commit();  // nor does this
  }
}

void TireGroup::work() {
  long served = 0;
  for (;;) {
    for (int spin = 0; spin < spins_ && round_.load(std::memory_order_acquire) == served; ++spin) pause();
    std::unique_lock<std::mutex> lock(mutex_);
    start_.wait(lock, [&] { return stopping_ || round_ != served; });
    if (stopping_) return;
    served = round_;
    lock.unlock();
    take_tires();
    lock.lock();
    if (--pending_ == 0) done_.notify_one();
  }
}

void TireGroup::run_lanes(Task task) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = task;
    next_tire_ = 0;
    pending_ = static_cast<int>(workers_.size());
    ++round_;
  }
  start_.notify_all();
  take_tires();
  for (int spin = 0; spin < spins_ && pending_.load(std::memory_order_acquire) != 0; ++spin) pause();
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return pending_ == 0; });
}

void TireGroup::serve_in_turn(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) {
  replies.resize(size());
  for (int i = 0; i < size(); ++i) replies[i] = spindle(i).serve(requests[i]);
}

void TireGroup::serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) {
  if (!concurrent_) {
    serve_in_turn(requests, replies);
    return;
  }
  replies.resize(size());
  requests_ = &requests;
  replies_ = &replies;
  run_lanes(Task::Serve);
}

void TireGroup::command_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  for (auto& request : commands_) request.command = command;
  if (concurrent_ && command == SpindleCommand::Commit) run_lanes(Task::PrepareCommit);
  serve_in_turn(commands_, replies);  // a commit's output, and reverts: in turn
}

}  // namespace tirefe
