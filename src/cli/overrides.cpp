#include "overrides.hpp"
#include "../errors.hpp"
#include <petscsys.h>

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
  const std::string opts = c.text("solver.petsc_options") + " " + extra;
  PetscOptionsInsertString(nullptr, opts.c_str());
}
} // namespace breastsim::cli
