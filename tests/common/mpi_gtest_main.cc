// GoogleTest main for every test binary: the same binary runs as a plain process (an MPI
// singleton) and under mpiexec. Only rank 0 prints the test log; every rank runs every test,
// so a failure on any rank still fails the run through its exit code.
#include <gtest/gtest.h>
#include <mpi.h>

#include "dem/parallel/mpi_start.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // Listing the tests (GoogleTest's discovery, at build time) starts no MPI: the sanitizer
  // build's leak check would count Open MPI's never-freed start-up allocations, and the
  // discovery runs without the tests' environment.
  if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
  // GoogleTest's discovery runs each test case as a process of its own: a singleton.
  upgrain::dem::prefer_isolated_singleton();
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) {
    ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int local = RUN_ALL_TESTS();
  int global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return global;
}
