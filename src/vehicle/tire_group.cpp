#include "vehicle/tire_group.hpp"

#include <algorithm>

namespace tirefe {

TireGroup::TireGroup(std::vector<TireSpindle*> tires, bool concurrent, int lanes)
    : TireExchange(std::move(tires)), commands_(size()) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  lanes_ = concurrent ? std::clamp(lanes > 0 ? lanes : cores, 1, std::max(1, size())) : 1;
  concurrent_ = lanes_ > 1;
  workers_.reserve(lanes_ - 1);
  for (int lane = 1; lane < lanes_; ++lane) workers_.emplace_back([this, lane] { work(lane); });
}

TireGroup::~TireGroup() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void TireGroup::serve_lane(int lane) {
  for (int tire = lane; tire < size(); tire += lanes_)
    (*replies_)[tire] = spindle(tire).serve((*requests_)[tire]);  // serve() never throws
}

void TireGroup::work(int lane) {
  long served = 0;
  for (;;) {
    std::unique_lock<std::mutex> lock(mutex_);
    start_.wait(lock, [&] { return stopping_ || round_ != served; });
    if (stopping_) return;
    served = round_;
    lock.unlock();
    serve_lane(lane);
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
  serve_lane(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return pending_ == 0; });
}

void TireGroup::command_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  for (auto& request : commands_) request.command = command;
  // Commit and revert are cheap bookkeeping (and commit writes output): in turn.
  serve_in_turn(commands_, replies);
}

}  // namespace tirefe
