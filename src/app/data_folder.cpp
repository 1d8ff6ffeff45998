// SPDX-License-Identifier: LGPL-3.0-or-later
#include "data_folder.hpp"
#include "errors.hpp"
#include "input_file.hpp"
#include "output_target.hpp"
#include "safe_write.hpp"
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
/// True if `p` is `q` or one of its ancestors.
bool is_same_or_ancestor(const fs::path& p, const fs::path& q)
{
  if (q.empty())
    return false;
  auto pi = p.begin(), qi = q.begin();
  for (; pi != p.end() && qi != q.end(); ++pi, ++qi)
    if (*pi != *qi)
      return false;
  return pi == p.end();
}

bool has_marker(const fs::path& dir)
{
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(dir / data_marker, ec)))
    return false; // a link is never breastsim's marker
  std::ifstream f(dir / data_marker);
  if (!f)
    return false;
  const auto j = nlohmann::json::parse(f, nullptr, false);
  return j.is_object() && j.value("written_by", "") == "breastsim";
}

std::string refusal(const fs::path& dir)
{
  const auto protect = ProtectedPaths::of_this_process();
  for (const auto& [p, what] : {std::pair{protect.root, "the file-system root"},
                                {protect.home, "$HOME"}, {protect.cwd, "the working directory"}})
    if (is_same_or_ancestor(dir, p))
      return fmt::format("it is {} or one of its ancestors", what);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    return "it is not a folder";
  if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec) && !has_marker(dir))
    return fmt::format("it is not empty and was not created by breastsim serve (no {} marker)",
                       data_marker);
  for (const char* own : {"jobs", data_marker}) // the server's own entries: never links
  {
    const auto st = fs::symlink_status(dir / own, ec);
    if (fs::is_symlink(st))
      return fmt::format("its '{}' is {}, which breastsim serve never creates", own,
                         entry_kind(dir / own));
  }
  return "";
}
} // namespace

fs::path claim_data_folder(const std::string& given)
{
  const fs::path dir = normalise_path(given, "--data");
  if (const auto why = refusal(dir); !why.empty())
    throw InputError(fmt::format("--data {}: refused: {}", dir.string(), why));
  fs::create_directories(dir / "jobs");
  if (!has_marker(dir))
  {
    try
    {
      write_file_nofollow(dir / data_marker,
                          nlohmann::json{{"written_by", "breastsim"},
                                         {"format", "breastsim-serve-data"},
                                         {"version", 1}}
                                  .dump(2)
                              + "\n",
                          Existing::refuse);
    }
    catch (const std::system_error& e)
    {
      throw InputError(fmt::format("--data {}: cannot write the marker {}: {}", dir.string(),
                                   data_marker, e.code().message()));
    }
  }
  return dir;
}
} // namespace breastsim::app
