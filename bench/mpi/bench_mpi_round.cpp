// bench_mpi_round: the cost of one round of tire replies between MPI ranks, without the
// tires: the MPI_Allgatherv of MpiTireGroup with four tires owned round-robin, as bytes
// of SpindleReply (docs/vehicle.md, "Performance").
//   mpirun -np 2 build/bench_mpi_round [rounds]
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "vehicle/spindle_exchange.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const int tires = 4, rounds = argc > 1 ? std::atoi(argv[1]) : 20000;
  std::vector<int> bytes(ranks, 0), offsets(ranks, 0);
  for (int i = 0; i < tires; ++i) bytes[i % ranks] += static_cast<int>(sizeof(tirefe::SpindleReply));
  for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + bytes[r - 1];
  std::vector<tirefe::SpindleReply> mine(bytes[rank] / sizeof(tirefe::SpindleReply)), all(tires);
  auto round = [&] {
    MPI_Allgatherv(mine.data(), bytes[rank], MPI_BYTE, all.data(), bytes.data(), offsets.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
  };
  for (int k = 0; k < rounds / 10; ++k) round();  // warm-up
  const double start = MPI_Wtime();
  for (int k = 0; k < rounds; ++k) round();
  const double seconds = (MPI_Wtime() - start) / rounds;
  if (rank == 0)
    std::printf("%d ranks, %d tires: %.2f us per round of replies (%zu bytes each)\n", ranks, tires, 1e6 * seconds,
                sizeof(tirefe::SpindleReply));
  MPI_Finalize();
  return 0;
}
