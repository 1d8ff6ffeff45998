// SPDX-License-Identifier: LGPL-3.0-or-later
#include "checkpoint.hpp"
#include "errors.hpp"
#include "input_file.hpp"
#include "safe_write.hpp"
#include "log.hpp"
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace breastsim::calibration
{
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& cp)
{
  if (!log::is_root())
    return;
  nlohmann::json j;
  j["parameters"] = cp.names;
  j["best_log_values"] = cp.best_y;
  std::vector<double> p;
  for (double y : cp.best_y)
    p.push_back(std::exp(y));
  j["best_values"] = p;
  j["best_chi2"] = cp.best_chi2;
  j["evaluations"] = cp.evaluations;
  j["written_by"] = "breastsim";
  if (file.has_parent_path())
    std::filesystem::create_directories(file.parent_path());
  const auto tmp = file.string() + fmt::format(".tmp-{}", getpid());
  try
  {
    write_file_nofollow(tmp, j.dump(2) + "\n", Existing::refuse); // a new file, never through a link
    std::filesystem::rename(tmp, file);
  }
  catch (const std::exception& e)
  {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(fmt::format("cannot write the checkpoint '{}': {}", file.string(),
                                         plain_error(e)));
  }
}

Checkpoint read_checkpoint(const std::filesystem::path& file, const std::vector<FitParameter>& fit)
{
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("--resume: checkpoint '{}' does not exist (run without --resume "
                                 "first)",
                                 file.string()));
  Checkpoint cp;
  try
  {
    const auto j = nlohmann::json::parse(in);
    cp.names = j.at("parameters").get<std::vector<std::string>>();
    cp.best_y = j.at("best_log_values").get<std::vector<double>>();
    cp.best_chi2 = j.at("best_chi2").get<double>();
    cp.evaluations = j.at("evaluations").get<int>();
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(fmt::format("--resume: checkpoint '{}' is damaged: {}", file.string(), plain_error(e)));
  }
  std::vector<std::string> want;
  for (const auto& p : fit)
    want.push_back(p.name);
  if (cp.names != want || cp.best_y.size() != want.size())
    throw InputError(fmt::format("--resume: checkpoint '{}' fits [{}], not the requested --fit {}",
                                 file.string(), fmt::join(cp.names, ","), fmt::join(want, ",")));
  for (std::size_t i = 0; i < fit.size(); ++i)
  {
    const double p = std::exp(cp.best_y[i]);
    if (!std::isfinite(p) || p < fit[i].lower || p > fit[i].upper)
      throw InputError(fmt::format("--resume: checkpoint '{}': {} = {} lies outside the search "
                                   "bounds [{}, {}] of this case",
                                   file.string(), fit[i].name, p, fit[i].lower, fit[i].upper));
  }
  return cp;
}
} // namespace breastsim::calibration
