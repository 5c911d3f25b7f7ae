#include "tile_ranks.h"

#include <cstdio>
#include <cstdlib>

#include "skyview/core/error.h"

#ifdef SKYVIEW_WITH_MPI
// MPI's C interface only: OpenMPI's C++ bindings do not compile under -Wextra -Werror.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace skyview::cli {

namespace {

// The ranks mpirun launched, from its environment (OpenMPI, then MPICH's PMI); 1 without mpirun.
int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  }
  return 1;
}

#ifdef SKYVIEW_WITH_MPI
constexpr int kReady = 1, kTile = 2, kDone = 3;
#endif

}  // namespace

TileRanks& TileRanks::world() {
  static TileRanks ranks;
  return ranks;
}

TileRanks::TileRanks() {
  if (launched_ranks() <= 1) return;
#ifdef SKYVIEW_WITH_MPI
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) MPI_Init(nullptr, nullptr);
  started_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  std::atexit([] {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised) MPI_Finalize();
  });
#else
  throw Error("this skyview was built without MPI (libopenmpi-dev), so it cannot share tiles between the " +
              std::to_string(launched_ranks()) + " ranks mpirun started; run it without mpirun, or rebuild with MPI");
#endif
}

void TileRanks::serve(const std::vector<int>& todo,
                      const std::function<void(int tile, const std::string& record)>& done) {
#ifdef SKYVIEW_WITH_MPI
  std::size_t next = 0;
  int stopped = 0;
  while (stopped < size_ - 1) {
    MPI_Status status;
    MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kDone) {
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string message(static_cast<std::size_t>(length), '\0');
      MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, kDone, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const std::size_t cut = message.find('\n');
      done(std::stoi(message.substr(0, cut)), message.substr(cut + 1));
    } else {
      int ignored = 0;
      MPI_Recv(&ignored, 1, MPI_INT, status.MPI_SOURCE, kReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
    const int tile = next < todo.size() ? todo[next++] : -1;
    stopped += tile < 0;
    MPI_Send(&tile, 1, MPI_INT, status.MPI_SOURCE, kTile, MPI_COMM_WORLD);
  }
#else
  (void)todo;
  (void)done;
#endif
}

void TileRanks::work(const std::function<std::string(int tile)>& work) {
#ifdef SKYVIEW_WITH_MPI
  const int ready = 0;
  MPI_Send(&ready, 1, MPI_INT, 0, kReady, MPI_COMM_WORLD);
  for (;;) {
    int tile = -1;
    MPI_Recv(&tile, 1, MPI_INT, 0, kTile, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (tile < 0) return;
    const std::string message = std::to_string(tile) + "\n" + work(tile);
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kDone, MPI_COMM_WORLD);
  }
#else
  (void)work;
#endif
}

void TileRanks::abort(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "skyview %s: error: %s%s\n", command.c_str(),
               rank_ > 0 ? ("rank " + std::to_string(rank_) + ": ").c_str() : "", message.c_str());
  std::fflush(stderr);
#ifdef SKYVIEW_WITH_MPI
  if (started_) MPI_Abort(MPI_COMM_WORLD, 1);
#endif
  std::_Exit(1);
}

void TileRanks::finish_worker() {
  std::fflush(stdout);
  std::fflush(stderr);
  std::exit(0);  // MPI_Finalize runs at exit
}

}  // namespace skyview::cli
