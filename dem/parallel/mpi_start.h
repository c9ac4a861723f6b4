#pragma once
// Before MPI_Init: a process started without a launcher (an MPI singleton: a test case, or
// `upgrain scene.prm` on one rank) needs no runtime daemon and no transport but the self one.
// Open MPI spawns the daemon for a singleton unless told otherwise, which costs about 0.5 s
// per process; isolated it starts in 0.05 s. The user's own settings win.
#include <mpi.h>

#include <cstdlib>

namespace upgrain::dem {

inline void prefer_isolated_singleton() {
  if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr) return;  // started by mpirun
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
}

}  // namespace upgrain::dem

namespace upgrain::dem {

// MPI for the life of a small program's main() (examples, benchmarks): initialised with
// prefer_isolated_singleton(), finalised at the end of the scope.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv) {
    prefer_isolated_singleton();
    MPI_Init(&argc, &argv);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

}  // namespace upgrain::dem
