// The MPI build: ranks share the cases; results travel to rank 0 as serialised strings, so the
// ranks need no shared file system.
#include <mpi.h>

#include <cstdlib>

#include "distribution.hpp"

namespace topomill::cli {

Distribution::Distribution() {
  // Only under a launcher: a plain `topomill sweep` in an MPI build stays a single process.
  const bool launched =
      std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
  if (!launched) return;
  MPI_Init(nullptr, nullptr);
  mpi_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
}

Distribution::~Distribution() {
  if (mpi_) MPI_Finalize();
}

Distribution& Distribution::instance() {
  static Distribution d;
  return d;
}

std::vector<std::string> Distribution::gather(const std::vector<std::string>& mine) const {
  if (!mpi_) return mine;
  // One buffer per rank: the strings joined with '\0'.
  std::string packed;
  for (const auto& s : mine) packed += s + '\0';
  int size = static_cast<int>(packed.size());
  std::vector<int> sizes(ranks_), offsets(ranks_);
  MPI_Gather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank_ == 0) {
    int total = 0;
    for (int r = 0; r < ranks_; ++r) offsets[r] = total, total += sizes[r];
    all.resize(total);
  }
  MPI_Gatherv(packed.data(), size, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0,
              MPI_COMM_WORLD);
  if (rank_ != 0) return mine;
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all[i] == '\0') out.push_back(all.substr(start, i - start)), start = i + 1;
  return out;
}

}  // namespace topomill::cli
