// TireExchange: how a vehicle asks its tires, wherever they are solved. Every request of
// a round goes to its own tire and every tire's answer comes back; the implementations
// differ in where the tires are solved: TireGroup in this process (in threads),
// MpiTireGroup (src/parallel/) on the MPI ranks that own them. The vehicle sees the
// tires through the replies only: the spindle force of a committed step comes back with
// the Commit reply and is kept here, so that a process whose copy of a tire does not
// advance (another rank solves it) knows it all the same.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "vehicle/tire_spindle.hpp"

namespace tirefe {

class TireExchange {
 public:
  /// The tires as they are when the vehicle is made (the same in every process that runs
  /// the deck); they must outlive the exchange.
  explicit TireExchange(std::vector<TireSpindle*> tires);
  virtual ~TireExchange() = default;
  TireExchange(const TireExchange&) = delete;
  TireExchange& operator=(const TireExchange&) = delete;

  int size() const { return static_cast<int>(tires_.size()); }
  /// Tire i as it was when the exchange was made: its spin, design position and start
  /// time. A tire solved in another process does not advance here.
  const TireSpindle& tire(int i) const { return *tires_[i]; }

  /// replies[i] = tire i's answer to requests[i].
  virtual void serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) = 0;
  /// The same command to every tire; keeps the committed forces of a Commit.
  void serve_all(SpindleCommand command, std::vector<SpindleReply>& replies);
  /// Spindle force of tire i at its committed step (the force on the tire, physical).
  const Eigen::Vector3d& committed_force(int i) const { return committed_forces_[i]; }

 protected:
  TireSpindle& spindle(int i) { return *tires_[i]; }
  /// serve_all() without the bookkeeping. Commit writes output: in turn, not in threads.
  virtual void command_all(SpindleCommand command, std::vector<SpindleReply>& replies) = 0;

 private:
  std::vector<TireSpindle*> tires_;
  std::vector<Eigen::Vector3d> committed_forces_;
};

}  // namespace tirefe
