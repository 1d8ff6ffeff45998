#pragma once
// Shared CLI helpers: load a case with --set overrides; pass PETSc options.
#include "../config.hpp"
#include <string>
#include <vector>

namespace breastsim::cli
{
/// Load CASE.toml (every default if `file` is empty) and apply "key=value" overrides (validated).
Config load_case(const std::string& file, const std::vector<std::string>& sets);
/// Insert the case's solver.petsc_options and the command line's into PETSc.
void insert_petsc_options(const Config& c, const std::string& extra);
} // namespace breastsim::cli
