#include "vehicle/tire_group.hpp"

#include <thread>

namespace tirefe {

TireGroup::TireGroup(std::vector<TireSpindle*> tires, bool concurrent)
    : tires_(std::move(tires)), concurrent_(concurrent), commands_(tires_.size()) {}

void TireGroup::serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) {
  replies.resize(tires_.size());
  const size_t count = tires_.size();
  if (!concurrent_ || count < 2) {
    for (size_t i = 0; i < count; ++i) replies[i] = tires_[i]->serve(requests[i]);
    return;
  }
  // One thread per tire but the first, which this thread solves; serve() never throws.
  std::vector<std::thread> workers;
  workers.reserve(count - 1);
  for (size_t i = 1; i < count; ++i)
    workers.emplace_back([this, i, &requests, &replies] { replies[i] = tires_[i]->serve(requests[i]); });
  replies[0] = tires_[0]->serve(requests[0]);
  for (auto& worker : workers) worker.join();
}

void TireGroup::serve_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  for (auto& request : commands_) request.command = command;
  // Commit and revert are cheap bookkeeping (and commit writes output): in turn.
  replies.resize(tires_.size());
  for (size_t i = 0; i < tires_.size(); ++i) replies[i] = tires_[i]->serve(commands_[i]);
}

}  // namespace tirefe
