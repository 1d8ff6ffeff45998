// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Checked PETSc calls and owning PETSc handles.
//
//   PETSC_CHECK(VecNorm(b, NORM_2, &n));
// throws PetscCallError naming the failing call, its file and line, and PETSc's
// own message for the error code. Owning handles destroy their object when
// they go out of scope (also when an exception unwinds the stack):
//   PetscVec b(model.create_vector());   // VecDestroy at scope exit
//   VecNorm(b.get(), NORM_2, &n);
#include <petscksp.h>
#include <petscmat.h>
#include <petscsys.h>
#include <petscvec.h>
#include <stdexcept>
#include <string>
#include <utility>

namespace breastsim
{
/// A PETSc call that returned an error code (an internal failure: exit code 1).
class PetscCallError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Throw PetscCallError for `code` returned by `call` at file:line.
[[noreturn]] inline void throw_petsc_error(PetscErrorCode code, const char* call, const char* file,
                                           int line)
{
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw PetscCallError(std::string("PETSc call ") + call + " failed (" + file + ":" + std::to_string(line)
                   + "): error " + std::to_string(static_cast<int>(code)) + (text ? ", " : "")
                   + (text ? text : ""));
}

/// A PETSc object that this handle owns and destroys with Destroy.
template <typename Handle, PetscErrorCode (*Destroy)(Handle*)>
class PetscOwned
{
public:
  PetscOwned() = default;
  /// Take ownership of h (may be nullptr).
  explicit PetscOwned(Handle h) : _h(h) {}
  ~PetscOwned() { reset(); }
  PetscOwned(const PetscOwned&) = delete;
  PetscOwned& operator=(const PetscOwned&) = delete;
  PetscOwned(PetscOwned&& o) noexcept : _h(std::exchange(o._h, nullptr)) {}
  PetscOwned& operator=(PetscOwned&& o) noexcept
  {
    if (this != &o)
    {
      reset();
      _h = std::exchange(o._h, nullptr);
    }
    return *this;
  }
  Handle get() const { return _h; }
  /// For PETSc's create functions: `MatCreate(comm, a.out())`; destroys the
  /// object held before.
  Handle* out()
  {
    reset();
    return &_h;
  }
  /// Destroy the object now (nothing if empty).
  void reset()
  {
    if (_h)
      Destroy(&_h);
    _h = nullptr;
  }
  /// Give up ownership: the caller destroys the returned object.
  Handle release() { return std::exchange(_h, nullptr); }
  explicit operator bool() const { return _h != nullptr; }

private:
  Handle _h = nullptr;
};

using PetscVec = PetscOwned<Vec, VecDestroy>;
using PetscMat = PetscOwned<Mat, MatDestroy>;
using PetscKsp = PetscOwned<KSP, KSPDestroy>;
using PetscIs = PetscOwned<IS, ISDestroy>;
} // namespace breastsim

/// Call a PETSc function and throw breastsim::PetscCallError if it fails.
#define PETSC_CHECK(call)                                                                          \
  do                                                                                               \
  {                                                                                                \
    const PetscErrorCode breastsim_petsc_code_ = (call);                                           \
    if (breastsim_petsc_code_ != 0)                                                                \
      ::breastsim::throw_petsc_error(breastsim_petsc_code_, #call, __FILE__, __LINE__);            \
  } while (0)
