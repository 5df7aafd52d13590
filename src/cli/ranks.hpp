// The ranks of a sweep (issue 16): `mpirun -n K collide2d props|study ...`
// runs K copies of the program, rank 0 to K − 1. MPI is started only by the
// sweeping commands and only when the program was launched by mpirun (its
// environment says so); otherwise, or in a build without MPI, there is one
// rank and no MPI call is made, so every other command, and a sweep run
// directly, never touches MPI.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace collide2d::cli {

struct Ranks {
  int rank = 0;
  int size = 1;
  bool mpi = false;  // MPI_Init was called (stop_ranks finalizes it)
};

// Starts MPI if launched by mpirun (thread level "funneled": only the main
// thread calls MPI). Throws std::runtime_error when mpirun started several
// ranks of a build without MPI: each would take every case and write the
// same file.
Ranks start_ranks();

// Rank 0's list reaches every rank (MPI_Bcast), with its verdict on the
// command: `refusal` 0 to go on, else the exit code every rank returns (rank
// 0 has said why). With one rank it returns its arguments as they are.
struct RootDecision {
  int refusal = 0;
  std::vector<std::int64_t> items;
};
RootDecision broadcast_from_root(const Ranks& ranks, RootDecision decision);

// MPI_Finalize, after a sweep that ended normally on every rank.
void stop_ranks(const Ranks& ranks);

// "Open MPI v4.1.4, ..." (the library's own words), or "built without MPI".
std::string mpi_library_description();

// The ranks a build of this program can run (for --help and the README).
bool built_with_mpi();

}  // namespace collide2d::cli
