// SPDX-License-Identifier: LGPL-3.0-or-later
// Checked PETSc calls and owning PETSc handles (src/core/petsc.hpp).
#include "petsc.hpp"
#include <gtest/gtest.h>
#include <string>

using namespace breastsim;

namespace
{
/// A sequential vector of n entries. Caller owns.
Vec new_vector(PetscInt n)
{
  Vec v;
  VecCreateSeq(PETSC_COMM_SELF, n, &v);
  return v;
}

PetscInt references(Vec v)
{
  PetscInt n = -1;
  PetscObjectGetReference(reinterpret_cast<PetscObject>(v), &n);
  return n;
}

/// PETSc's error handler for the test's deliberate failures: the code is
/// returned without PETSc printing a traceback.
class QuietPetscErrors
{
public:
  QuietPetscErrors() { PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr); }
  ~QuietPetscErrors() { PetscPopErrorHandler(); }
};
} // namespace

// A failing call throws PetscError naming the call, where it was made and
// PETSc's message for the error code; a call that succeeds does nothing.
TEST(PetscCheck, ThrowsPetscErrorNamingTheCall)
{
  PetscVec v(new_vector(4));
  PetscInt n = 0;
  PETSC_CHECK(VecGetSize(v.get(), &n));
  EXPECT_EQ(n, 4);
  QuietPetscErrors quiet;
  const PetscErrorCode code = VecSetType(v.get(), "no_such_vector_type"); // PETSc's own verdict
  ASSERT_NE(code, 0);
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  ASSERT_NE(text, nullptr);
  try
  {
    PETSC_CHECK(VecSetType(v.get(), "no_such_vector_type"));
    FAIL() << "an unknown vector type is refused";
  }
  catch (const breastsim::PetscCallError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("VecSetType(v.get(), \"no_such_vector_type\")"), std::string::npos) << what;
    EXPECT_NE(what.find("test_petsc.cpp:"), std::string::npos) << what;
    EXPECT_NE(what.find("error " + std::to_string(code)), std::string::npos) << what;
    EXPECT_NE(what.find(text), std::string::npos) << what;
  }
  // A PetscError is a std::runtime_error (callers that catch those see it).
  EXPECT_THROW(PETSC_CHECK(VecSetSizes(v.get(), 5, 5)), std::runtime_error);
}

// An owning handle destroys its object when it goes out of scope, also when
// an exception unwinds the stack; reset, move, out() and release() pass the
// ownership on as documented.
TEST(PetscHandles, DestroyTheirObjectOnce)
{
  Vec v = new_vector(3);
  PetscObjectReference(reinterpret_cast<PetscObject>(v)); // the test's own reference
  ASSERT_EQ(references(v), 2);
  {
    PetscVec h(v);
    EXPECT_EQ(h.get(), v);
  }
  EXPECT_EQ(references(v), 1) << "the handle's reference is released at scope exit";

  PetscObjectReference(reinterpret_cast<PetscObject>(v));
  try
  {
    QuietPetscErrors quiet;
    PetscVec h(v);
    PETSC_CHECK(VecSetType(h.get(), "no_such_vector_type"));
  }
  catch (const breastsim::PetscCallError&)
  {
  }
  EXPECT_EQ(references(v), 1) << "the handle's reference is released while unwinding";

  PetscObjectReference(reinterpret_cast<PetscObject>(v));
  PetscVec a(v);
  PetscVec b(std::move(a));
  EXPECT_FALSE(a);
  EXPECT_EQ(b.get(), v);
  EXPECT_EQ(references(v), 2) << "a move transfers the reference";
  b.reset();
  EXPECT_FALSE(b);
  EXPECT_EQ(b.get(), nullptr);
  EXPECT_EQ(references(v), 1);

  PetscObjectReference(reinterpret_cast<PetscObject>(v));
  PetscVec c(v);
  Vec released = c.release();
  EXPECT_FALSE(c);
  EXPECT_EQ(released, v);
  EXPECT_EQ(references(v), 2) << "release gives up the reference without destroying";
  VecDestroy(&released);
  EXPECT_EQ(references(v), 1);

  // out() destroys the object held before a create function fills it.
  PetscObjectReference(reinterpret_cast<PetscObject>(v));
  PetscVec d(v);
  VecDuplicate(v, d.out());
  EXPECT_EQ(references(v), 1);
  EXPECT_NE(d.get(), v);
  EXPECT_NE(d.get(), nullptr);
  VecDestroy(&v);
}

// A matrix and a KSP held by handles, moved into another handle by move
// assignment: the object held before is destroyed, the moved one survives.
TEST(PetscHandles, MoveAssignmentDestroysTheOldObject)
{
  Mat A;
  MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 1, nullptr, &A);
  PetscObjectReference(reinterpret_cast<PetscObject>(A));
  PetscMat held(A);
  PetscMat other;
  PETSC_CHECK(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 1, nullptr, other.out()));
  held = std::move(other);
  PetscInt refs = -1;
  PetscObjectGetReference(reinterpret_cast<PetscObject>(A), &refs);
  EXPECT_EQ(refs, 1);
  PetscInt rows = 0, cols = 0;
  PETSC_CHECK(MatGetSize(held.get(), &rows, &cols));
  EXPECT_EQ(rows, 3);
  MatDestroy(&A);

  PetscKsp ksp;
  PETSC_CHECK(KSPCreate(PETSC_COMM_SELF, ksp.out()));
  EXPECT_TRUE(ksp);
  ksp.reset();
  EXPECT_FALSE(ksp);
}
