#include "vehicle/tire_group.hpp"

namespace tirefe {

TireGroup::TireGroup(std::vector<TireSpindle*> tires, bool concurrent)
    : tires_(std::move(tires)), concurrent_(concurrent && tires_.size() > 1), commands_(tires_.size()) {
  if (!concurrent_) return;
  workers_.reserve(tires_.size() - 1);
  for (size_t i = 1; i < tires_.size(); ++i) workers_.emplace_back([this, i] { work(i); });
}

TireGroup::~TireGroup() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void TireGroup::work(size_t tire) {
  long served = 0;
  for (;;) {
    std::unique_lock<std::mutex> lock(mutex_);
    start_.wait(lock, [&] { return stopping_ || round_ != served; });
    if (stopping_) return;
    served = round_;
    lock.unlock();
    (*replies_)[tire] = tires_[tire]->serve((*requests_)[tire]);  // serve() never throws
    lock.lock();
    if (--pending_ == 0) done_.notify_one();
  }
}

void TireGroup::serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) {
  replies.resize(tires_.size());
  if (!concurrent_) {
    for (size_t i = 0; i < tires_.size(); ++i) replies[i] = tires_[i]->serve(requests[i]);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    requests_ = &requests;
    replies_ = &replies;
    pending_ = static_cast<int>(workers_.size());
    ++round_;
  }
  start_.notify_all();
  replies[0] = tires_[0]->serve(requests[0]);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return pending_ == 0; });
}

void TireGroup::serve_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  for (auto& request : commands_) request.command = command;
  // Commit and revert are cheap bookkeeping (and commit writes output): in turn.
  replies.resize(tires_.size());
  for (size_t i = 0; i < tires_.size(); ++i) replies[i] = tires_[i]->serve(commands_[i]);
}

}  // namespace tirefe
