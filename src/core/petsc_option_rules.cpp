// SPDX-License-Identifier: LGPL-3.0-or-later
#include "petsc_option_rules.hpp"
#include <algorithm>
#include <cctype>
#include <fmt/format.h>
#include <sstream>

namespace breastsim
{
namespace
{
bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }
bool ends_with(const std::string& s, const std::string& p)
{
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}
bool contains(const std::string& s, const std::string& p) { return s.find(p) != std::string::npos; }

/// "-name" with a letter after the dash: an option, not a negative number.
bool is_option_token(const std::string& t)
{
  return t.size() > 1 && t[0] == '-' && std::isalpha(static_cast<unsigned char>(t[1]));
}

std::string unquote(std::string t)
{
  if (t.size() >= 2 && (t.front() == '"' || t.front() == '\'') && t.back() == t.front())
    return t.substr(1, t.size() - 2);
  return t;
}

/// Options that read or write files, start programs or open windows, whatever their value.
bool refused_by_name(const std::string& n)
{
  static const std::vector<std::string> exact
      = {"-history", "-display", "-x_virtual", "-on_error_emacs", "-log", "-log_all",
         "-log_trace", "-log_mpe", "-log_perfstubs", "-objects_dump"};
  static const std::vector<std::string> prefixes
      = {"-options_file", "-viewer_", "-draw_", "-saws_", "-python", "-mpi_linear_solver_server"};
  return std::find(exact.begin(), exact.end(), n) != exact.end()
         || std::any_of(prefixes.begin(), prefixes.end(), [&](const auto& p) { return starts_with(n, p); })
         || contains(n, "debugger");
}

/// Options whose value is a PETSc viewer (where and how to print).
bool is_viewer_option(const std::string& n)
{
  return ends_with(n, "_view") || contains(n, "_view_") || ends_with(n, "_converged_reason")
         || contains(n, "monitor") || starts_with(n, "-log_") || starts_with(n, "-info")
         || starts_with(n, "-malloc_") || starts_with(n, "-memory_");
}

/// A viewer value that prints to standard output: "", "ascii", "::FORMAT", "ascii::FORMAT".
bool is_stdout_viewer(const std::string& v)
{
  if (v.empty() || v == "ascii")
    return true;
  const std::string rest = starts_with(v, "ascii") ? v.substr(5) : v;
  return starts_with(rest, "::") && rest.find(':', 2) == std::string::npos
         && std::all_of(rest.begin() + 2, rest.end(),
                        [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
}
} // namespace

std::vector<PetscOption> parse_petsc_options(const std::string& text)
{
  std::vector<PetscOption> options;
  std::istringstream is(text);
  std::string t;
  while (is >> t)
  {
    if (is_option_token(t) || options.empty())
      options.push_back({t, ""});
    else
      options.back().value += (options.back().value.empty() ? "" : " ") + unquote(t);
  }
  return options;
}

std::optional<std::string> petsc_options_refusal(const std::string& text)
{
  for (const auto& [name, value] : parse_petsc_options(text))
  {
    if (!is_option_token(name))
      return fmt::format("'{}' is not a PETSc option (options start with '-')", name);
    if (refused_by_name(name))
      return fmt::format("PETSc option {} is not accepted: it reads or writes files, or starts "
                         "another program",
                         name);
    if (is_viewer_option(name))
    {
      if (is_stdout_viewer(value))
        continue;
      return fmt::format("PETSc option {} {} is not accepted: viewer options may only print to "
                         "standard output (no value, \"ascii\" or \"::FORMAT\")",
                         name, value);
    }
    if (contains(value, "/") || contains(value, ":") || value == "python")
      return fmt::format("PETSc option {} {} is not accepted: its value names a file or a "
                         "program",
                         name, value);
  }
  return std::nullopt;
}
} // namespace breastsim
