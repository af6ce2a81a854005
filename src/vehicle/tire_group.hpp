// TireGroup: the tires of a vehicle behind their spindles, asked together. Every
// request of a round goes to its own tire; with concurrency each tire is solved in its
// own thread (the tires share nothing, so the replies are those of a sequential round,
// bit for bit). A tire in another process would sit behind the same requests and
// replies (spindle_exchange.hpp, docs/spindle.md).
#pragma once

#include <vector>

#include "vehicle/tire_spindle.hpp"

namespace tirefe {

class TireGroup {
 public:
  /// The spindles must outlive the group.
  TireGroup(std::vector<TireSpindle*> tires, bool concurrent);

  int size() const { return static_cast<int>(tires_.size()); }
  TireSpindle& tire(int i) { return *tires_[i]; }
  bool concurrent() const { return concurrent_; }
  void set_concurrent(bool concurrent) { concurrent_ = concurrent; }

  /// replies[i] = tire i's answer to requests[i].
  void serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies);
  /// The same command to every tire.
  void serve_all(SpindleCommand command, std::vector<SpindleReply>& replies);

 private:
  std::vector<TireSpindle*> tires_;
  bool concurrent_;
  std::vector<SpindleRequest> commands_;
};

}  // namespace tirefe
