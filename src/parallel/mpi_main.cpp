// tirefe-mpi: runs an input deck on every rank of an MPI job, the tires of its vehicles
// solved on the ranks that own their models (docs/vehicle.md, "Concurrency and processes").
//   mpirun -np N tirefe-mpi deck.lua [key=value ...] [--output-dir DIR] [--quiet] [--verbose]
// Every rank runs the whole deck. Rank 0 alone prints (the others' standard output goes
// to /dev/null); each rank writes the result files of the models it owns.
// Ending: an error every rank meets (the deck is replicated: nearly every error) is
// printed once, by rank 0, and every rank exits with the tirefe status. An error some
// ranks meet alone (a model read after another rank advanced it) is printed by them, and
// if the other ranks do not end too within 10 s (they may be waiting for the
// failed rank in a round of tire replies), the job is ended with MPI_Abort.
#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <thread>

#include "app/deck_runner.hpp"
#include "app/program_heap.hpp"
#include "parallel/mpi_tire_group.hpp"

namespace {

using tirefe::macros::DeckOutcome;

constexpr double kEndingWait = 10.0;  // [s] for the other ranks to end as well after an error

/// True once every rank has called this; false after 'seconds' (negative: no limit).
/// On its own communicator: a rank still waiting in a round of tire replies must not
/// take this barrier for its collective.
bool all_ranks_ended(MPI_Comm ending, double seconds) {
  MPI_Request request;
  MPI_Ibarrier(ending, &request);
  const double deadline = MPI_Wtime() + seconds;
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (seconds >= 0.0 && MPI_Wtime() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // idle: ranks may share cores
  }
}

/// The exit status every rank agrees on, with the error printed once.
int end_run(const DeckOutcome& outcome, int rank, MPI_Comm ending) {
  std::fflush(stdout);
  if (!all_ranks_ended(ending, outcome.status == 0 ? -1.0 : kEndingWait)) {
    std::cerr << "[rank " << rank << "] " << outcome.error << std::flush;
    MPI_Abort(MPI_COMM_WORLD, outcome.status);
  }
  int lowest = 0, highest = 0;
  MPI_Allreduce(&outcome.status, &lowest, 1, MPI_INT, MPI_MIN, ending);
  MPI_Allreduce(&outcome.status, &highest, 1, MPI_INT, MPI_MAX, ending);
  if (lowest == highest) {
    if (rank == 0) std::cerr << outcome.error;
  } else if (outcome.status != 0) {
    std::cerr << "[rank " << rank << "] " << outcome.error;
  }
  return highest;
}

}  // namespace

int main(int argc, char** argv) {
  tirefe::macros::keep_row_buffers_in_heap();
  int provided = 0, rank = 0, ranks = 1;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // tire threads never call MPI
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (rank != 0 && !std::freopen("/dev/null", "w", stdout)) std::fclose(stdout);
  MPI_Comm ending;
  MPI_Comm_dup(MPI_COMM_WORLD, &ending);

  DeckOutcome outcome;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--restart") == 0)
      outcome = {2, "tirefe-mpi: --restart is not supported on MPI ranks: restart with tirefe\n"};
  if (outcome.status == 0) {
    outcome = tirefe::macros::run_deck_command(argc, argv, [&](tirefe::macros::DeckSession& session) {
      session.processes = {rank, ranks};
      if (rank != 0) session.progress.draw_on(nullptr);  // rank 0 alone shows the progress line
      session.tire_exchange = [](std::vector<tirefe::TireSpindle*> tires, std::vector<int> owners, bool threads) {
        return std::make_unique<tirefe::MpiTireGroup>(std::move(tires), owners, threads, MPI_COMM_WORLD);
      };
    });
  }
  const int status = end_run(outcome, rank, ending);
  MPI_Comm_free(&ending);
  MPI_Finalize();
  return status;
}
