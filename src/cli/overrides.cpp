// SPDX-License-Identifier: LGPL-3.0-or-later
#include "overrides.hpp"
#include "errors.hpp"
#include "petsc.hpp"
#include "petsc_option_rules.hpp"
#include "strings.hpp"
#include "output_options.hpp"
#include "solver_options.hpp"
#include <fmt/format.h>
#include <petscksp.h>

// PETSc-style functions: they return PETSc error codes (PetscCall).
namespace
{
/// PETSc error handler that keeps the first message (the one naming the option).
PetscErrorCode keep_message(MPI_Comm, int, const char*, const char*, PetscErrorCode n, PetscErrorType,
                            const char* mess, void* ctx)
{
  auto* s = static_cast<std::string*>(ctx);
  if (s->empty() && mess)
    *s = mess;
  return n;
}

/// Set a KSP up from the options on a 2x2 identity: unknown types and bad
/// values fail here, before any solve. PETSc's error code, not an exception:
/// the caller reports the message its error handler kept.
PetscErrorCode probe_solver()
{
  breastsim::PetscMat A;
  breastsim::PetscKsp ksp;
  PetscCall(MatCreateAIJ(PETSC_COMM_SELF, 2, 2, 2, 2, 1, nullptr, 0, nullptr, A.out()));
  for (PetscInt i = 0; i < 2; ++i)
    PetscCall(MatSetValue(A.get(), i, i, 1.0, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(A.get(), MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A.get(), MAT_FINAL_ASSEMBLY));
  PetscCall(KSPCreate(PETSC_COMM_SELF, ksp.out()));
  PetscCall(KSPSetOperators(ksp.get(), A.get(), A.get()));
  PetscCall(KSPSetFromOptions(ksp.get()));
  PetscCall(KSPSetUp(ksp.get()));
  return 0;
}
} // namespace

namespace breastsim::cli
{
Config load_case(const std::string& file, const std::vector<std::string>& sets)
{
  Config c = file.empty() ? Config() : Config::from_file(file);
  for (const auto& s : sets)
  {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set expects key=value, got '" + s + "'");
    c.set_text(s.substr(0, eq), s.substr(eq + 1));
  }
  c.validate();
  return c;
}

void insert_petsc_options(const Config& c, const std::string& extra)
{
  const std::string from_case = SolverOptions::from(c).petsc_options;
  if (auto why = petsc_options_refusal(from_case))
    throw InputError(fmt::format("key 'solver.petsc_options' = \"{}\": {}", shorten(from_case), *why));
  if (auto why = petsc_options_refusal(extra))
    throw InputError(fmt::format("--petsc-options \"{}\": {}", shorten(extra), *why));
  const std::string opts = from_case + " " + extra;
  std::string message;
  PETSC_CHECK(PetscPushErrorHandler(keep_message, &message));
  PetscErrorCode rc = PetscOptionsInsertString(nullptr, opts.c_str());
  if (rc == 0)
    rc = probe_solver();
  PETSC_CHECK(PetscPopErrorHandler());
  if (rc != 0)
    throw InputError(fmt::format("PETSc options \"{}\" (solver.petsc_options and --petsc-options) "
                                 "are refused by PETSc: {}",
                                 shorten(opts),
                                 message.empty() ? "error " + std::to_string(rc) : message));
}

void add_output_option(CLI::App* app, OutputOption& o, const std::string& help)
{
  o.option = app->add_option("--out", o.out, help + "; only a folder breastsim wrote (it holds a "
                                        ".breastsim-result marker) is replaced");
  app->add_flag("--force", o.force, "allow --out to be an existing empty folder that breastsim "
                                    "did not write");
}

namespace
{
OutputRules rules_for(bool force, const std::vector<std::string>& inputs)
{
  OutputRules r;
  r.force = force;
  for (const auto& f : inputs)
    if (!f.empty())
      r.inputs.emplace_back(f);
  return r;
}
} // namespace

std::string output_name(const OutputOption& o, const std::string& default_out)
{
  if (o.option && o.option->count() > 0 && o.out.empty())
    throw InputError("--out is empty: give a folder name");
  return o.out.empty() ? default_out : o.out;
}

OutputTarget claim_output(const OutputOption& o, const std::string& default_out,
                          const std::vector<std::string>& inputs)
{
  return OutputTarget::claim(output_name(o, default_out), rules_for(o.force, inputs), MPI_COMM_WORLD);
}

std::filesystem::path claim_file(const std::string& file, const std::vector<std::string>& inputs,
                                 const std::string& what)
{
  return claim_output_file(file, rules_for(false, inputs), what);
}
std::string pictures_hint(const Config& c, const std::filesystem::path& dir)
{
  if (OutputOptions::from(c).pictures_on())
    return "";
  return fmt::format("pictures and the 3D page: breastsim view {}\n", dir.string());
}
} // namespace breastsim::cli
