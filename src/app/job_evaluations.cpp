// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_evaluations.hpp"
#include "errors.hpp"
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
nlohmann::json finite_or_null(const nlohmann::json& v)
{
  return v.is_number() && std::isfinite(v.get<double>()) ? v : nlohmann::json();
}
} // namespace

nlohmann::json evaluations_from_history(const nlohmann::json& history)
{
  auto out = nlohmann::json::array();
  for (const auto& h : history)
    out.push_back({{"n", h.at("evaluation")},
                   {"chi2", finite_or_null(h.at("chi2"))},
                   {"params", h.value("parameters", nlohmann::json::object())},
                   {"stage", h.value("stage", "")},
                   {"best", h.value("best", false)}});
  return out;
}

nlohmann::json complete_json_lines(const std::string& jsonl)
{
  auto out = nlohmann::json::array();
  std::istringstream in(jsonl);
  std::string line;
  while (std::getline(in, line))
  {
    if (in.eof() && !jsonl.empty() && jsonl.back() != '\n')
      break; // the last line is still being written
    auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_object())
      out.push_back(std::move(j));
  }
  return out;
}

nlohmann::json evaluations_after(const std::string& jsonl, long since)
{
  auto out = nlohmann::json::array();
  for (auto& j : complete_json_lines(jsonl))
    if (j.contains("n") && j["n"].is_number_integer() && j.contains("chi2") && j["n"].get<long>() > since)
      out.push_back(std::move(j));
  return out;
}

long parse_since(const std::string& text)
{
  if (text.empty())
    return 0;
  long v = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < 0 || v > 1000000000)
    throw InputError("since = '" + text.substr(0, 40) + "': allowed an integer in [0, 1000000000]");
  return v;
}

void append_evaluation(const fs::path& folder, const nlohmann::json& entry)
{
  std::ofstream f(folder / evaluations_file, std::ios::app);
  f << entry.dump() << "\n";
  f.flush();
}

void write_evaluations(const fs::path& folder, const nlohmann::json& entries)
{
  const fs::path tmp = folder / (std::string(evaluations_file) + ".tmp");
  {
    std::ofstream f(tmp, std::ios::trunc);
    for (const auto& e : entries)
      f << e.dump() << "\n";
    if (!f)
      throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, folder / evaluations_file);
}

nlohmann::json read_evaluations(const fs::path& folder, long since)
{
  std::ifstream f(folder / evaluations_file);
  if (!f)
    return nlohmann::json::array();
  std::ostringstream s;
  s << f.rdbuf();
  return evaluations_after(s.str(), since);
}
} // namespace breastsim::app
