#pragma once
// The ranks of an `mpirun` sharing a --tiles-dir run's tiles: rank 0 hands out tile indices from a
// queue, one at a time as ranks ask (tiles of a city differ in cost, so no static split), computes
// tiles from the same queue itself and records each finished tile; the other ranks compute and
// write the tiles they are given. The same executable run without mpirun (or with one rank) is
// single-process and never starts MPI. MPI runs at MPI_THREAD_FUNNELED: only the main thread of a
// rank calls it.
#include <functional>
#include <string>
#include <vector>

namespace skyview::cli {

class TileRanks {
 public:
  // This process's ranks, MPI started on first use where mpirun launched more than one. Throws
  // skyview::Error where it did but this build has no MPI.
  static TileRanks& world();
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool parallel() const { return size_ > 1; }

  // Rank 0: hands out `todo` to every rank, itself included, and calls `done` (on this thread) with
  // each finished tile's record and the rank that made it, until every tile is done and every rank
  // told to stop. Rank 0's own tiles are computed by `work` on a thread of its own, while this one
  // waits on MPI without spinning (a probe every millisecond) so that the work has the cores.
  void serve(const std::vector<int>& todo, const std::function<std::string(int tile)>& work,
             const std::function<void(int tile, int rank, const std::string& record)>& done);
  // Other ranks: asks for tiles until none remain; `work` computes one and returns its record.
  void work(const std::function<std::string(int tile)>& work);
  // What `make` returns on rank 0 (which alone calls it), on every rank; the others wait without
  // spinning. Where `make` throws, rank 0 rethrows and the other ranks end quietly with exit code 1
  // (rank 0 prints the error).
  std::string broadcast(const std::function<std::string()>& make);
  // Prints `message` as the run's one error line and ends every rank with exit code 1.
  [[noreturn]] void abort(const std::string& command, const std::string& message);
  // Ends MPI (where started) and this process with `code`: for the ranks other than 0.
  [[noreturn]] void finish_worker(int code = 0);

 private:
  TileRanks();
  int rank_ = 0, size_ = 1;
  bool started_ = false;
};

}  // namespace skyview::cli
