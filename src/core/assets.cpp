// SPDX-License-Identifier: LGPL-3.0-or-later
#include "assets.hpp"
#include <cstdlib>
#include <stdexcept>

namespace breastsim
{
namespace fs = std::filesystem;

std::filesystem::path asset_dir(const std::string& name, const char* variable)
{
  if (const char* v = std::getenv(variable); v && *v)
    return v;
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec).parent_path();
  const fs::path installed = program.parent_path() / "share" / "breastsim" / name;
  const fs::path build_tree = program / "share" / "breastsim" / name;
  for (const auto& p : {installed, build_tree})
    if (fs::is_directory(p, ec))
      return p;
  throw std::runtime_error("breastsim's " + name + " files are neither in " + installed.string()
                           + " nor in " + build_tree.string() + " (reinstall, or set "
                           + variable + ")");
}
} // namespace breastsim
