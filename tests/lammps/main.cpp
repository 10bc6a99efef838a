// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// main() of the library-API tests: MPI must be up before any LAMMPS instance is created.
#include <gtest/gtest.h>
#include <mpi.h>

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
