// TireGroup: the tires of a vehicle behind their spindles, asked together. Every
// request of a round goes to its own tire; with concurrency the tires are dealt to
// lanes, as many as there are cores (or tires, if fewer): tire i to lane i mod lanes.
// The calling thread serves lane 0, a worker thread each other lane (started once,
// waiting between rounds), so four tires on two cores make two threads, not four taking
// turns. The tires share nothing, so the replies are those of a sequential round, bit
// for bit. MpiTireGroup (src/parallel/) asks tires on other
// MPI ranks through the same requests and replies (tire_exchange.hpp, docs/spindle.md).
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "vehicle/tire_exchange.hpp"

namespace tirefe {

class TireGroup final : public TireExchange {
 public:
  /// The spindles must outlive the group. lanes: threads solving the tires (0: one per
  /// core of the machine), never more than the tires.
  TireGroup(std::vector<TireSpindle*> tires, bool concurrent, int lanes = 0);
  ~TireGroup() override;

  bool concurrent() const { return concurrent_; }
  int lanes() const { return lanes_; }

  void serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) override;

 protected:
  void command_all(SpindleCommand command, std::vector<SpindleReply>& replies) override;

 private:
  void work(int lane);
  void serve_lane(int lane);
  void serve_in_turn(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies);

  bool concurrent_;
  int lanes_ = 1;
  std::vector<SpindleRequest> commands_;
  // The round the workers serve: set under the mutex, read by the workers after it.
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  long round_ = 0;
  int pending_ = 0;
  bool stopping_ = false;
  const std::vector<SpindleRequest>* requests_ = nullptr;
  std::vector<SpindleReply>* replies_ = nullptr;
};

}  // namespace tirefe
