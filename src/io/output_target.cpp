// SPDX-License-Identifier: LGPL-3.0-or-later
#include "output_target.hpp"
#include "errors.hpp"
#include "input_file.hpp"
#include "safe_write.hpp"
#include "strings.hpp"
#include "interrupt.hpp"
#include "on_root.hpp"
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <algorithm>
#include <fstream>
#include <set>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace breastsim
{
namespace fs = std::filesystem;

namespace
{
constexpr const char* marker_format = "breastsim result folder";
std::string g_command_line = "breastsim";

/// `a` is `b` or one of its ancestors (both normalised).
bool is_ancestor_or_self(const fs::path& a, const fs::path& b)
{
  if (a.empty() || b.empty())
    return false;
  auto ia = a.begin(), ib = b.begin();
  for (; ia != a.end(); ++ia, ++ib)
    if (ib == b.end() || *ia != *ib)
      return false;
  return true;
}

std::string host_name()
{
  char buf[256] = {};
  gethostname(buf, sizeof buf - 1);
  return buf;
}

bool process_alive(long pid)
{
  return pid > 0 && (kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

/// An entry of a result folder that breastsim did not write, and why.
struct ForeignEntry
{
  fs::path path;
  std::string why;
};

/// The first entry below `dir` that the marker does not list, or that is a
/// symbolic link or a special file (breastsim writes neither), if any.
std::optional<ForeignEntry> foreign_entry(const fs::path& dir, const nlohmann::json& marker)
{
  std::set<std::string> listed, parents;
  for (const auto& f : marker.value("files", nlohmann::json::array()))
  {
    const fs::path p = f.get<std::string>();
    listed.insert(p.lexically_normal().string());
    for (fs::path q = p.parent_path(); !q.empty(); q = q.parent_path())
      parents.insert(q.string());
  }
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it); it.increment(ec))
  {
    const std::string rel = it->path().lexically_relative(dir).string();
    const auto st = it->symlink_status(ec);
    if (fs::is_symlink(st) || (!fs::is_directory(st) && !fs::is_regular_file(st)))
      return ForeignEntry{it->path(), fmt::format("which is {}; breastsim never writes one",
                                                  entry_kind(it->path()))};
    if (rel == result_marker)
      continue;
    if (fs::is_directory(st) ? parents.count(rel) == 0 && listed.count(rel) == 0 : listed.count(rel) == 0)
      return ForeignEntry{it->path(), "which breastsim did not write"};
  }
  if (ec)
    return ForeignEntry{dir, "which cannot be listed (" + ec.message() + ")"};
  return std::nullopt;
}

/// Why a marker's "files" list is not one breastsim writes: every entry a
/// relative path inside the folder (no root, no "..").
std::optional<std::string> bad_file_list(const nlohmann::json& m)
{
  if (!m.contains("files"))
    return std::nullopt;
  if (!m.at("files").is_array())
    return "its \"files\" is not a list";
  for (const auto& f : m.at("files"))
  {
    if (!f.is_string() || f.get<std::string>().empty())
      return "its \"files\" holds an entry that is not a file name";
    const fs::path p = f.get<std::string>();
    const bool escapes = std::any_of(p.begin(), p.end(), [](const fs::path& c) { return c == ".."; });
    if (p.has_root_path() || escapes)
      return fmt::format("its \"files\" lists '{}', which is not a path inside the folder",
                         shorten(f.get<std::string>()));
  }
  return std::nullopt;
}

std::string refuse(const fs::path& p, const std::string& why)
{
  return fmt::format("refusing to write the result into '{}': {}", p.string(), why);
}
} // namespace

ProtectedPaths ProtectedPaths::of_this_process()
{
  ProtectedPaths p;
  p.root = "/";
  if (const char* h = std::getenv("HOME"); h && *h)
    p.home = fs::weakly_canonical(fs::absolute(h));
  std::error_code ec;
  p.cwd = fs::current_path(ec);
  if (!ec)
    p.cwd = fs::weakly_canonical(p.cwd);
  return p;
}

fs::path normalise_path(const std::string& given, const std::string& what)
{
  if (given.empty())
    throw InputError(fmt::format("{} is empty: give a folder name", what));
  if (given.find('\0') != std::string::npos)
    throw InputError(fmt::format("{} contains a NUL character", what));
  fs::path p = fs::weakly_canonical(fs::absolute(given)); // resolves symlinks, "..", "."
  while (!p.has_filename() && p != p.root_path())          // trailing separator
    p = p.parent_path();
  return p;
}

namespace
{
/// Why `p` must never be written, whatever it holds: the root, $HOME, the
/// working directory or an ancestor of them, an input file or its ancestor.
std::optional<std::string> protected_reason(const fs::path& p, const OutputRules& rules)
{
  const ProtectedPaths& pp = rules.protect;
  if (p == pp.root || p == p.root_path())
    return "it is the file-system root";
  if (is_ancestor_or_self(p, pp.home))
    return pp.home == p ? "it is your home folder ($HOME)" : "it holds your home folder ($HOME)";
  if (is_ancestor_or_self(p, pp.cwd))
    return pp.cwd == p ? "it is the working directory" : "it holds the working directory";
  for (const auto& in : rules.inputs)
  {
    std::error_code ec;
    const fs::path f = fs::weakly_canonical(fs::absolute(in), ec);
    if (ec)
      continue;
    if (f == p)
      return fmt::format("it is an input file of this run ('{}')", in.string());
    if (is_ancestor_or_self(p, f.parent_path()))
      return fmt::format("it holds the input file '{}'", in.string());
  }
  return std::nullopt;
}
} // namespace

std::optional<std::string> refusal_reason(const fs::path& target, const OutputRules& rules)
{
  if (auto why = protected_reason(target, rules))
    return refuse(target, *why);
  std::error_code ec;
  const auto st = fs::symlink_status(target, ec);
  if (ec || !fs::exists(st))
    return std::nullopt; // a new folder
  if (fs::is_regular_file(st))
    return refuse(target, "it is a file, not a folder written by breastsim");
  if (!fs::is_directory(st))
    return refuse(target, fmt::format("it is {}, not a folder written by breastsim",
                                      entry_kind(target)));
  const auto marker_st = fs::symlink_status(target / result_marker, ec);
  if (fs::exists(marker_st) && !fs::is_regular_file(marker_st))
    return refuse(target, fmt::format("its {} is {}, which breastsim never writes", result_marker,
                                      entry_kind(target / result_marker)));
  if (!fs::exists(marker_st))
  {
    if (fs::is_empty(target, ec) && !ec)
      return rules.force ? std::nullopt
                         : std::optional<std::string>(refuse(
                             target, "the folder exists (empty) and was not written by breastsim; "
                                     "pass --force to use it"));
    return refuse(target, fmt::format("the folder is not empty and has no {} marker, so "
                                      "breastsim did not write it (choose a new folder)",
                                      result_marker));
  }
  nlohmann::json m;
  try
  {
    m = read_marker(target);
  }
  catch (const std::exception& e)
  {
    return refuse(target, fmt::format("its {} cannot be read: {}", result_marker, plain_error(e)));
  }
  if (m.value("state", "") != "complete")
    return refuse(target, "its marker says it is not a finished breastsim result");
  if (auto f = foreign_entry(target, m))
    return refuse(target, fmt::format("it holds '{}', {} (move it away or choose another folder)",
                                      f->path.lexically_relative(target).string(), f->why));
  return std::nullopt;
}

void set_command_line(int argc, char** argv)
{
  std::string s;
  for (int i = 0; i < argc; ++i)
    s += (i ? " " : "") + std::string(argv[i]);
  g_command_line = s;
}

nlohmann::json read_marker(const fs::path& dir)
{
  std::ifstream in(dir / result_marker);
  const auto m = nlohmann::json::parse(in);
  if (!m.is_object() || m.value("format", "") != marker_format)
    throw std::runtime_error(fmt::format("not a '{}' marker", marker_format));
  if (auto why = bad_file_list(m))
    throw std::runtime_error(*why);
  return m;
}

void write_marker(const fs::path& dir, const std::string& state)
{
  nlohmann::json files = nlohmann::json::array();
  if (state == "complete")
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (!e.is_directory() && e.path().lexically_relative(dir).string() != result_marker) // nested markers listed
        files.push_back(e.path().lexically_relative(dir).string());
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  const nlohmann::json m = {{"format", marker_format}, {"version", 1},
                            {"command", g_command_line}, {"created", when},
                            {"host", host_name()},      {"pid", static_cast<long>(getpid())},
                            {"state", state},          {"files", files}};
  try
  {
    write_file_nofollow(dir / result_marker, m.dump(2) + "\n");
  }
  catch (const std::system_error& e)
  {
    throw std::runtime_error(fmt::format("cannot write '{}': {}", (dir / result_marker).string(),
                                         e.code().message()));
  }
}

fs::path staging_path(const fs::path& target, long pid)
{
  return target.parent_path() / (target.filename().string() + ".partial-" + std::to_string(pid));
}

int remove_stale_staging(const fs::path& target)
{
  const std::string prefix = target.filename().string() + ".partial-";
  std::error_code ec;
  int removed = 0;
  for (const auto& e : fs::directory_iterator(target.parent_path(), ec))
  {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !e.is_directory() || e.is_symlink())
      continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    try
    {
      const auto m = read_marker(e.path());
      const long pid = m.value("pid", 0L);
      if (m.value("state", "") != "staging" || m.value("host", "") != host_name()
          || std::to_string(pid) != digits || process_alive(pid))
        continue;
    }
    catch (const std::exception&)
    {
      continue; // not ours: left alone
    }
    std::error_code rm;
    fs::remove_all(e.path(), rm);
    removed += rm ? 0 : 1;
  }
  return removed;
}

namespace
{
/// Open and flock `lock_file` (never through a symbolic link); InputError,
/// naming the target, if another run holds it or something else has its name.
/// Retries when the previous holder unlinked the file between our open and flock.
int acquire_lock(const fs::path& lock_file, const fs::path& target)
{
  auto no = [&](const std::string& why) { return InputError(refuse(target, why)); };
  for (int attempt = 0; attempt < 5; ++attempt)
  {
    std::error_code ec;
    const auto st = fs::symlink_status(lock_file, ec);
    if (fs::exists(st) && !fs::is_regular_file(st))
      throw no(fmt::format("'{}' beside it is {}, not breastsim's lock file (remove it)",
                           lock_file.filename().string(), entry_kind(lock_file)));
    const int fd = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0 && errno == ELOOP)
      throw no(fmt::format("'{}' beside it is a symbolic link, not breastsim's lock file (remove it)",
                           lock_file.filename().string()));
    if (fd < 0)
      throw no(fmt::format("cannot create a file in '{}': {}", lock_file.parent_path().string(),
                           std::strerror(errno)));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0)
    {
      ::close(fd);
      throw no("another breastsim run is writing there (wait for it to finish)");
    }
    struct stat a{}, b{};
    if (fstat(fd, &a) == 0 && ::lstat(lock_file.c_str(), &b) == 0 && a.st_ino == b.st_ino)
      return fd;
    ::close(fd);
  }
  throw no("another breastsim run keeps taking its lock");
}
} // namespace

OutputTarget OutputTarget::claim(const std::string& given, const OutputRules& rules, MPI_Comm comm)
{
  OutputTarget t({}, rules);
  on_root(comm,
          [&]
          {
            try
            {
              t._path = normalise_path(given);
              if (auto why = refusal_reason(t._path, rules))
                throw InputError(*why);
              fs::create_directories(t._path.parent_path());
              t._lock_file
                  = t._path.parent_path() / ("." + t._path.filename().string() + ".breastsim-lock");
              t._lock_fd = acquire_lock(t._lock_file, t._path);
              interrupt::register_path(t._lock_file);
              remove_stale_staging(t._path);
            }
            catch (const InputError&)
            {
              throw;
            }
            catch (const std::exception& e)
            {
              throw InputError(fmt::format("cannot prepare the result folder '{}': {}",
                                           shorten(given, 300), plain_error(e)));
            }
          });
  std::string p = t._path.string();
  broadcast(p, comm);
  t._path = p;
  return t;
}

OutputTarget::OutputTarget(OutputTarget&& o) noexcept
    : _path(std::move(o._path)), _rules(std::move(o._rules)), _lock_fd(o._lock_fd),
      _lock_file(std::move(o._lock_file))
{
  o._lock_fd = -1;
  o._lock_file.clear();
}

OutputTarget::~OutputTarget()
{
  if (_lock_fd < 0)
    return;
  std::error_code ec;
  fs::remove(_lock_file, ec); // unlinked while held; the next holder checks the inode
  interrupt::unregister_path(_lock_file);
  ::close(_lock_fd);
}

fs::path claim_output_file(const std::string& given, const OutputRules& rules, const std::string& what)
{
  // The folder normalised, the file's own name not resolved: a link there is refused below.
  const fs::path given_abs = fs::absolute(given);
  const fs::path p = fs::is_symlink(fs::symlink_status(given_abs))
                         ? normalise_path(given_abs.parent_path().string(), what) / given_abs.filename()
                         : normalise_path(given, what);
  auto no = [&](const std::string& why)
  { return InputError(fmt::format("refusing to write {} '{}': {}", what, p.string(), why)); };
  if (auto why = protected_reason(p, rules))
    throw no(*why);
  std::error_code ec;
  const auto st = fs::symlink_status(p, ec);
  if (ec || !fs::exists(st))
    return p;
  if (!fs::is_regular_file(st))
    throw no(fmt::format("it is {}, not a regular file written by breastsim", entry_kind(p)));
  try
  {
    std::ifstream in(p);
    const auto j = nlohmann::json::parse(in);
    if (j.is_object() && j.value("written_by", "").rfind("breastsim", 0) == 0)
      return p;
  }
  catch (const std::exception&)
  {
  }
  throw no("the file exists and was not written by breastsim (choose a new name)");
}
} // namespace breastsim
