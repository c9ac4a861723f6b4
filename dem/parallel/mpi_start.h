#pragma once
// Before MPI_Init: a process started without a launcher (an MPI singleton: a test case, or
// `upgrain scene.prm` on one rank) needs no runtime daemon and no transport but the self one.
// Open MPI spawns the daemon for a singleton unless told otherwise, which costs about 0.5 s
// per process; isolated it starts in 0.05 s. Isolated singletons started at the same moment
// (a test suite run in parallel) race to create the same session directory, and the loser's
// MPI_Init fails ("A call to mkdir was unable to create the desired directory ... File
// exists"); each therefore gets a session directory of its own, removed at exit. The user's
// own settings win.
#include <mpi.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace upgrain::dem {

namespace detail {
inline std::string& singleton_session_base() {
  static std::string base;
  return base;
}
inline void remove_singleton_session_base() {
  std::error_code ec;
  if (!singleton_session_base().empty()) std::filesystem::remove_all(singleton_session_base(), ec);
}
}  // namespace detail

// MPI-IO through ROMIO: Open MPI 4.1.4's own MPI-IO (OMPIO, its default, with fcoll/vulcan)
// writes wrong bytes into parallel HDF5 files now and then (seen here in one or two of the seven
// snapshots of a 200-grain run on 4 ranks; Open MPI bug report github.com/open-mpi/ompi/issues/12718, fixed
// after 4.1.6). The snapshots are written collectively (dem/io/hdf5_snapshot.h). The user's own choice wins.
inline void prefer_romio() { setenv("OMPI_MCA_io", "romio321", 0); }

inline void prefer_isolated_singleton() {
  prefer_romio();
  if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr) return;  // started by mpirun
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  if (std::getenv("OMPI_MCA_orte_tmpdir_base") == nullptr) {
    std::error_code ec;
    const std::filesystem::path base =
        std::filesystem::temp_directory_path(ec) / ("upgrain-mpi-" + std::to_string(::getpid()));
    if (!ec && std::filesystem::create_directories(base, ec) && !ec) {
      detail::singleton_session_base() = base.string();
      setenv("OMPI_MCA_orte_tmpdir_base", base.c_str(), 1);
      std::atexit(detail::remove_singleton_session_base);
    }
  }
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
