#include "tile_ranks.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

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
  // Rank 0 computes tiles on a second thread, which never calls MPI.
  int provided = 0;
  if (!initialised) MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
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

void TileRanks::serve(const std::vector<int>& todo, const std::function<std::string(int tile)>& work,
                      const std::function<void(int tile, int rank, const std::string& record)>& done) {
  // The queue, shared by the other ranks (through this thread) and rank 0's own worker thread.
  std::mutex lock;
  std::size_t next = 0;
  bool stop = false;  // an error here: the worker takes no more tiles
  auto take = [&] {
    const std::lock_guard<std::mutex> hold(lock);
    return !stop && next < todo.size() ? todo[next++] : -1;
  };
  std::deque<std::pair<int, std::string>> finished;  // rank 0's, not yet recorded
  std::exception_ptr failure;
  bool worker_done = false;
  std::thread worker([&] {
    try {
      for (int tile; (tile = take()) >= 0;) {
        std::string record = work(tile);
        const std::lock_guard<std::mutex> hold(lock);
        finished.emplace_back(tile, std::move(record));
      }
    } catch (...) {
      const std::lock_guard<std::mutex> hold(lock);
      failure = std::current_exception();
    }
    const std::lock_guard<std::mutex> hold(lock);
    worker_done = true;
  });
  try {
    int stopped = 0;  // ranks told that no tile is left
    for (;;) {
      std::deque<std::pair<int, std::string>> mine;
      bool all_mine = false;
      {
        const std::lock_guard<std::mutex> hold(lock);
        if (failure) std::rethrow_exception(failure);
        mine.swap(finished);
        all_mine = worker_done;
      }
      for (const auto& [tile, record] : mine) done(tile, 0, record);
      if (all_mine && stopped == size_ - 1) break;
#ifdef SKYVIEW_WITH_MPI
      int waiting = 0;
      MPI_Status status;
      if (stopped < size_ - 1) MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
      if (!waiting) {
        // A blocking probe would poll busily (OpenMPI) and take a core from rank 0's own tiles.
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      if (status.MPI_TAG == kDone) {
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        std::string message(static_cast<std::size_t>(length), '\0');
        MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, kDone, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        const std::size_t cut = message.find('\n');
        done(std::stoi(message.substr(0, cut)), status.MPI_SOURCE, message.substr(cut + 1));
      } else {
        int ignored = 0;
        MPI_Recv(&ignored, 1, MPI_INT, status.MPI_SOURCE, kReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
      const int tile = take();
      stopped += tile < 0;
      MPI_Send(&tile, 1, MPI_INT, status.MPI_SOURCE, kTile, MPI_COMM_WORLD);
#else
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
#endif
    }
  } catch (...) {
    {
      const std::lock_guard<std::mutex> hold(lock);
      stop = true;
    }
    worker.join();  // after the tile it is on
    throw;
  }
  worker.join();
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

std::string TileRanks::broadcast(const std::function<std::string()>& make) {
  if (!parallel()) return make();
#ifdef SKYVIEW_WITH_MPI
  std::string bytes;
  std::uint64_t size = 0;
  int ok = 1;
  std::exception_ptr failure;
  if (rank_ == 0) {
    try {
      bytes = make();
      size = bytes.size();
    } catch (...) {
      failure = std::current_exception();
      ok = 0;
    }
  }
  // The other ranks wait here while rank 0 makes the bytes (reads the whole raster): without
  // spinning, as in serve.
  MPI_Request request;
  MPI_Ibcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  int arrived = 0;
  MPI_Test(&request, &arrived, MPI_STATUS_IGNORE);
  while (!arrived) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    MPI_Test(&request, &arrived, MPI_STATUS_IGNORE);
  }
  if (!ok) {
    if (rank_ == 0) std::rethrow_exception(failure);
    finish_worker(1);
  }
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(static_cast<std::size_t>(size));
  // In pieces: an MPI count is an int.
  constexpr std::uint64_t kPiece = std::uint64_t{1} << 30;
  for (std::uint64_t at = 0; at < size; at += kPiece)
    MPI_Bcast(bytes.data() + at, static_cast<int>(std::min(kPiece, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
  return bytes;
#else
  return make();
#endif
}

void TileRanks::finish_worker(int code) {
  std::fflush(stdout);
  std::fflush(stderr);
  std::exit(code);  // MPI_Finalize runs at exit
}

}  // namespace skyview::cli
