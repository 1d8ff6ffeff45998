// SPDX-License-Identifier: LGPL-3.0-or-later
// GoogleTest entry point: PETSc/MPI are initialised once for all tests.
#include <dolfinx/common/log.h>
#include <gtest/gtest.h>
#include <petscsys.h>

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  PetscInitializeNoArguments();
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
  const int code = RUN_ALL_TESTS();
  PetscFinalize();
  return code;
}
