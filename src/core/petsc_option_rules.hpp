// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Which PETSc options a case file or the command line may pass. PETSc options
// can read and write files, start debuggers and open windows; a case file
// someone shares must not be able to do any of that. Refused:
//  - by name: -options_file*, -history, -viewer_*, -draw_*, -display,
//    -x_virtual, debugger options, -on_error_emacs, -log, -log_all,
//    -log_trace, -log_mpe, -log_perfstubs, -objects_dump, -saws_*,
//    -python*, -mpi_linear_solver_server*;
//  - viewer options (names ending in _view or _converged_reason, or holding
//    _view_ or monitor, or starting with -log_, -info, -malloc_, -memory_)
//    with a value other than an ASCII viewer on standard output ("ascii",
//    "::FORMAT", "ascii::FORMAT");
//  - any value that names a path (holds '/' or ':') or the "python" type.
#include <optional>
#include <string>
#include <vector>

namespace breastsim
{
/// One option and its value ("" if none), as PETSc reads an options string.
struct PetscOption
{
  std::string name, value;
};

/// Split an options string into options (whitespace separated; a token that
/// does not start with '-' followed by a letter is the previous option's value).
std::vector<PetscOption> parse_petsc_options(const std::string& text);

/// Why `text` must not be passed to PETSc, naming the option, or nothing.
std::optional<std::string> petsc_options_refusal(const std::string& text);
} // namespace breastsim
