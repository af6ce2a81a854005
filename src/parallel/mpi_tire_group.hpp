// MpiTireGroup: the tires of a vehicle on the MPI ranks that own them (docs/vehicle.md,
// "Concurrency and processes"). Every rank runs the same deck and the same vehicle, so
// every rank sends the same requests; each rank solves the tires it owns (in threads, as
// a TireGroup, when asked to) and then one MPI_Allgatherv gives every rank every reply,
// as bytes (the ranks are one build on one kind of machine). A failed tire comes back as
// status Failed on every rank, so every rank's vehicle cuts its step or stops alike.
// Only the main thread calls MPI (MPI_THREAD_FUNNELED).
#pragma once

#include <mpi.h>

#include <memory>
#include <vector>

#include "vehicle/tire_exchange.hpp"
#include "vehicle/tire_group.hpp"

namespace tirefe {

class MpiTireGroup final : public TireExchange {
 public:
  /// owners[i]: the rank of 'comm' that solves tire i; on the other ranks tire i stays as it is.
  MpiTireGroup(std::vector<TireSpindle*> tires, const std::vector<int>& owners, bool concurrent, MPI_Comm comm);

  void serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) override;

 protected:
  void command_all(SpindleCommand command, std::vector<SpindleReply>& replies) override;

 private:
  /// local_replies_ of every rank into replies, by tire.
  void share(std::vector<SpindleReply>& replies);

  MPI_Comm comm_;
  std::vector<int> local_;                       // the tires this rank solves, ascending
  std::unique_ptr<TireGroup> solver_;            // local_ in this process
  std::vector<int> gathered_tire_;               // tire of each gathered reply: rank 0's tires first, ...
  std::vector<int> byte_counts_, byte_offsets_;  // per rank, in the gathered replies
  std::vector<SpindleRequest> local_requests_;
  std::vector<SpindleReply> local_replies_, gathered_;
};

}  // namespace tirefe
