#pragma once
// The ranks of an `mpirun` sharing a --tiles-dir run's tiles: rank 0 hands out tile indices from a
// queue, one at a time as ranks ask (tiles of a city differ in cost, so no static split), and
// records each finished tile; the other ranks compute and write the tiles they are given. The same
// executable run without mpirun (or with one rank) is single-process and never starts MPI.
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

  // Rank 0: hands out `todo` to the other ranks and calls `done` with each finished tile's record,
  // until every tile is done and every rank told to stop.
  void serve(const std::vector<int>& todo, const std::function<void(int tile, const std::string& record)>& done);
  // Other ranks: asks for tiles until none remain; `work` computes one and returns its record.
  void work(const std::function<std::string(int tile)>& work);
  // Prints `message` as the run's one error line and ends every rank with exit code 1.
  [[noreturn]] void abort(const std::string& command, const std::string& message);
  // Ends MPI (where started) and this process with exit code 0: for the ranks that only work.
  [[noreturn]] void finish_worker();

 private:
  TileRanks();
  int rank_ = 0, size_ = 1;
  bool started_ = false;
};

}  // namespace skyview::cli
