#include "vehicle/tire_group.hpp"

namespace tirefe {

TireGroup::TireGroup(std::vector<TireSpindle*> tires, bool concurrent)
    : TireExchange(std::move(tires)), concurrent_(concurrent && size() > 1), commands_(size()) {
  if (!concurrent_) return;
  workers_.reserve(size() - 1);
  for (int i = 1; i < size(); ++i) workers_.emplace_back([this, i] { work(i); });
}

TireGroup::~TireGroup() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void TireGroup::work(int tire) {
  long served = 0;
  for (;;) {
    std::unique_lock<std::mutex> lock(mutex_);
    start_.wait(lock, [&] { return stopping_ || round_ != served; });
    if (stopping_) return;
    served = round_;
    lock.unlock();
    (*replies_)[tire] = spindle(tire).serve((*requests_)[tire]);  // serve() never throws
    lock.lock();
    if (--pending_ == 0) done_.notify_one();
  }
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
  {
    std::lock_guard<std::mutex> lock(mutex_);
    requests_ = &requests;
    replies_ = &replies;
    pending_ = static_cast<int>(workers_.size());
    ++round_;
  }
  start_.notify_all();
  replies[0] = spindle(0).serve(requests[0]);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return pending_ == 0; });
}

void TireGroup::command_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  for (auto& request : commands_) request.command = command;
  // Commit and revert are cheap bookkeeping (and commit writes output): in turn.
  serve_in_turn(commands_, replies);
}

}  // namespace tirefe
