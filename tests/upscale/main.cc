// GoogleTest main for the upscale tests: the same binary runs as a plain process (an MPI
// singleton) and under mpiexec. MPI_InitFinalize also sets up p4est for the distributed
// mesh; one thread per rank. Only rank 0 prints the test log; every rank runs every test,
// and a failure on any rank fails the run through the exit code.
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0) {
    ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int local = RUN_ALL_TESTS();
  return dealii::Utilities::MPI::max(local, MPI_COMM_WORLD);
}
