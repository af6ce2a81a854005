#include "parallel/mpi_tire_group.hpp"

#include <algorithm>
#include <thread>

namespace tirefe {

MpiTireGroup::MpiTireGroup(std::vector<TireSpindle*> tires, const std::vector<int>& owners, bool concurrent,
                           MPI_Comm comm)
    : TireExchange(tires), comm_(comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &ranks);
  std::vector<TireSpindle*> mine;
  byte_counts_.assign(ranks, 0);
  byte_offsets_.assign(ranks, 0);
  for (int r = 0; r < ranks; ++r) {
    byte_offsets_[r] = static_cast<int>(gathered_tire_.size() * sizeof(SpindleReply));
    for (int i = 0; i < size(); ++i) {
      if (owners[i] != r) continue;
      gathered_tire_.push_back(i);
      byte_counts_[r] += static_cast<int>(sizeof(SpindleReply));
      if (r == rank) {
        local_.push_back(i);
        mine.push_back(tires[i]);
      }
    }
  }
  // The ranks on this machine share its cores: each gets its share of lanes, so that
  // threads never outnumber the cores (a waiting lane spins while it has one).
  MPI_Comm node;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
  int ranks_here = 1;
  MPI_Comm_size(node, &ranks_here);
  MPI_Comm_free(&node);
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  solver_ = std::make_unique<TireGroup>(std::move(mine), concurrent, std::max(1, cores / ranks_here));
  local_requests_.resize(local_.size());
  gathered_.resize(gathered_tire_.size());
}

void MpiTireGroup::serve(const std::vector<SpindleRequest>& requests, std::vector<SpindleReply>& replies) {
  for (size_t k = 0; k < local_.size(); ++k) local_requests_[k] = requests[local_[k]];
  solver_->serve(local_requests_, local_replies_);
  share(replies);
}

void MpiTireGroup::command_all(SpindleCommand command, std::vector<SpindleReply>& replies) {
  solver_->serve_all(command, local_replies_);
  share(replies);
}

void MpiTireGroup::share(std::vector<SpindleReply>& replies) {
  local_replies_.resize(local_.size());
  MPI_Allgatherv(local_replies_.data(), static_cast<int>(local_replies_.size() * sizeof(SpindleReply)), MPI_BYTE,
                 gathered_.data(), byte_counts_.data(), byte_offsets_.data(), MPI_BYTE, comm_);
  replies.resize(size());
  for (size_t k = 0; k < gathered_.size(); ++k) replies[gathered_tire_[k]] = gathered_[k];
}

}  // namespace tirefe
