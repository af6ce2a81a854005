#include "vehicle/tire_exchange.hpp"

namespace tirefe {

TireExchange::TireExchange(std::vector<TireSpindle*> tires) : tires_(std::move(tires)) {
  for (const TireSpindle* tire : tires_) committed_forces_.push_back(tire->committed_force());
}

void TireExchange::serve_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  command_all(command, replies);
  if (command != SpindleCommand::Commit) return;
  for (size_t i = 0; i < tires_.size(); ++i)
    if (replies[i].status == SpindleStatus::Ok) committed_forces_[i] = force_of(replies[i]);
}

}  // namespace tirefe
