// TireGroup: the tires of a vehicle behind their spindles, asked together, in this
// process. With concurrency, lanes (as many as there are cores, or tires if fewer) solve
// the tires of a round: the calling thread is lane 0, a worker thread each other lane
// (started once, waiting between rounds), and each lane takes the next tire not yet
// taken, so a tire crossing a pothole does not hold back the lane that also has a tire
// on the flat. Commit computes in the lanes too (the state moving on, the energies) and
// writes output in turn (HDF5 takes one call at a time: even built thread-safe it holds
// one lock for all; each result file's flushes go to its own writer thread, result_file.hpp).
// The tires share nothing, so the replies are those of a sequential round, bit for bit.
// MpiTireGroup (src/parallel/) asks tires on other MPI ranks through the same requests and
// replies (tire_exchange.hpp, docs/spindle.md).
#pragma once

#include <atomic>
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

  int lanes() const { return lanes_; }

  void serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) override;

 protected:
  void command_all(SpindleCommand command, std::vector<SpindleReply>& replies) override;

 private:
  /// What the lanes do with each tire of a round.
  enum class Task { Serve, PrepareCommit };
  void work();
  void run_lanes(Task task);
  void take_tires();
  void serve_in_turn(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies);

  bool concurrent_ = false;
  int lanes_ = 1;
  int spins_ = 0;  // pauses a waiting lane spins before it sleeps
  std::vector<SpindleRequest> commands_;
  // The round the lanes work on: set under the mutex, read by the workers after it.
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  std::atomic<long> round_{0};
  std::atomic<int> pending_{0};
  bool stopping_ = false;
  Task task_ = Task::Serve;
  std::atomic<int> next_tire_{0};
  const std::vector<SpindleRequest>* requests_ = nullptr;
  std::vector<SpindleReply>* replies_ = nullptr;
};

}  // namespace tirefe
