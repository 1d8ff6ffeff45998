// SPDX-License-Identifier: LGPL-3.0-or-later
#include "progress_channel.hpp"
#include "job_evaluations.hpp"
#include <algorithm>
#include <fstream>
#include <memory>
#include <mpi.h>

namespace breastsim::app
{
namespace fs = std::filesystem;

Progress progress_into(const fs::path& folder)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0)
    return {};
  auto count = std::make_shared<long>(0);
  const fs::path file = folder / progress_file;
  return Progress([file, count](const std::string& stage, double fraction) {
    std::ofstream f(file, std::ios::app);
    f << nlohmann::json{{"n", ++*count}, {"stage", stage}, {"fraction", fraction}}.dump() << "\n";
    f.flush();
  });
}

nlohmann::json progress_entries(const std::string& jsonl)
{
  auto out = nlohmann::json::array();
  for (auto& j : complete_json_lines(jsonl))
    if (j.contains("n") && j.contains("stage") && j["stage"].is_string() && j.contains("fraction") &&
        j["fraction"].is_number())
      out.push_back(std::move(j));
  return out;
}

JobProgress last_progress(const std::string& jsonl)
{
  const auto entries = progress_entries(jsonl);
  if (entries.empty())
    return {};
  const auto& last = entries.back();
  return {std::clamp(last["fraction"].get<double>(), 0.0, 0.99), last["stage"].get<std::string>()};
}
} // namespace breastsim::app
