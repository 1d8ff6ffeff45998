// SPDX-License-Identifier: LGPL-3.0-or-later
#include "input_file.hpp"
#include "errors.hpp"
#include <cerrno>
#include <fmt/format.h>
#include <unistd.h>

namespace breastsim
{
namespace fs = std::filesystem;

namespace
{
std::string kind_of(const fs::file_status& st)
{
  switch (st.type())
  {
  case fs::file_type::regular: return "a regular file";
  case fs::file_type::directory: return "a folder";
  case fs::file_type::symlink: return "a symbolic link";
  case fs::file_type::fifo: return "a named pipe (FIFO)";
  case fs::file_type::socket: return "a socket";
  case fs::file_type::block:
  case fs::file_type::character: return "a device";
  case fs::file_type::not_found: return "missing";
  default: return "not a regular file";
  }
}
} // namespace

std::string entry_kind(const fs::path& p)
{
  std::error_code ec;
  const auto st = fs::symlink_status(p, ec);
  if (ec)
    return "unreadable (" + ec.message() + ")";
  if (!fs::is_symlink(st))
    return kind_of(st);
  const auto target = fs::status(p, ec);
  if (ec && ec.value() == ELOOP)
    return "a symbolic link in a loop";
  if (ec || !fs::exists(target))
    return "a symbolic link to nothing";
  return "a symbolic link to " + kind_of(target);
}

void check_input_file(const fs::path& path, const std::string& what)
{
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (ec && ec.value() == ELOOP)
    throw InputError(fmt::format("{} '{}' cannot be read: it is a loop of symbolic links", what,
                                 path.string()));
  if (!fs::exists(st))
  {
    const bool dangling = fs::is_symlink(fs::symlink_status(path, ec));
    throw InputError(fmt::format("{} '{}' {}", what, path.string(),
                                 dangling ? "cannot be read: it is a symbolic link to nothing"
                                          : "does not exist"));
  }
  if (!fs::is_regular_file(st))
    throw InputError(fmt::format("{} '{}' is {}, not a regular file", what, path.string(),
                                 kind_of(st)));
  if (::access(path.c_str(), R_OK) != 0)
    throw InputError(fmt::format("{} '{}' cannot be read: {}", what, path.string(),
                                 std::generic_category().message(errno)));
}

std::string plain_error(const std::exception& e)
{
  if (const auto* fe = dynamic_cast<const fs::filesystem_error*>(&e))
  {
    std::string s = fe->code().message();
    if (!fe->path1().empty())
      s += " ('" + fe->path1().string() + "')";
    return s;
  }
  if (const auto* se = dynamic_cast<const std::system_error*>(&e))
    return se->code().message();
  std::string s = e.what();
  if (s.rfind("[json.exception.", 0) == 0) // nlohmann's "[json.exception.parse_error.101] ..."
    if (const auto end = s.find("] "); end != std::string::npos)
      s = s.substr(end + 2);
  return s;
}
} // namespace breastsim
