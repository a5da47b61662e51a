// How the cases of a sweep are shared among processes: one process alone, or the ranks of an MPI
// job (built with TOPOMILL_MPI=ON and started by mpirun). The single-machine build needs no MPI.
#pragma once

#include <string>
#include <vector>

namespace topomill::cli {

class Distribution {
 public:
  // Starts MPI when the program was built with it and runs under mpirun; otherwise rank 0 of 1.
  static Distribution& instance();
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  // Every rank's strings, concatenated in rank order on rank 0; the caller's own elsewhere.
  std::vector<std::string> gather(const std::vector<std::string>& mine) const;
  ~Distribution();

 private:
  Distribution();
  int rank_ = 0, ranks_ = 1;
  bool mpi_ = false;
};

}  // namespace topomill::cli
