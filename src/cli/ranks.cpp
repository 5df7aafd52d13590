#include "cli/ranks.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef COLLIDE2D_HAVE_MPI
#include <mpi.h>
#endif

namespace collide2d::cli {
namespace {

// The number of ranks mpirun says it started (Open MPI, MPICH/Hydra, PMIx),
// or 0 when not launched by mpirun.
int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"})
    if (const char* v = std::getenv(name); v && *v) return std::atoi(v);
  return 0;
}

}  // namespace

bool built_with_mpi() {
#ifdef COLLIDE2D_HAVE_MPI
  return true;
#else
  return false;
#endif
}

Ranks start_ranks() {
  Ranks ranks;
  const int launched = launcher_world_size();
  if (launched == 0) return ranks;
#ifdef COLLIDE2D_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error("the MPI library does not allow a second thread beside MPI (MPI_THREAD_FUNNELED)");
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &ranks.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks.size);
  ranks.mpi = true;
#else
  if (launched > 1)
    throw std::runtime_error("launched by mpirun with " + std::to_string(launched) +
                             " ranks, but this build has no MPI (configure with Open MPI installed: "
                             "apt-get install libopenmpi-dev); run it without mpirun");
#endif
  return ranks;
}

RootDecision broadcast_from_root(const Ranks& ranks, RootDecision decision) {
#ifdef COLLIDE2D_HAVE_MPI
  if (!ranks.mpi) return decision;
  std::int64_t head[2] = {decision.refusal, static_cast<std::int64_t>(decision.items.size())};
  MPI_Bcast(head, 2, MPI_INT64_T, 0, MPI_COMM_WORLD);
  decision.refusal = static_cast<int>(head[0]);
  decision.items.resize(static_cast<std::size_t>(head[1]));
  if (head[1] > 0) MPI_Bcast(decision.items.data(), static_cast<int>(head[1]), MPI_INT64_T, 0, MPI_COMM_WORLD);
#else
  (void)ranks;
#endif
  return decision;
}

void stop_ranks(const Ranks& ranks) {
#ifdef COLLIDE2D_HAVE_MPI
  if (ranks.mpi) MPI_Finalize();
#else
  (void)ranks;
#endif
}

std::string mpi_library_description() {
#ifdef COLLIDE2D_HAVE_MPI
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string s(text, static_cast<std::size_t>(length));
  if (const auto end = s.find_first_of(",\n"); end != std::string::npos) s.resize(end);
  return s;
#else
  return "built without MPI";
#endif
}

}  // namespace collide2d::cli
