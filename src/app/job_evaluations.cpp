#include "job_evaluations.hpp"
#include "errors.hpp"
#include <charconv>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
/// A number of the library's text ("350.4", "1.48e+05", "inf", "nan"), or nullopt.
std::optional<double> number_of(const std::string& text)
{
  if (text.empty())
    return std::nullopt;
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double v = 0;
  if (text == "inf" || text == "-inf" || text == "nan" || text == "-nan")
    return std::nan("");
  in >> v;
  if (in.fail() || !in.eof())
    return std::nullopt;
  return v;
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }
} // namespace

std::optional<nlohmann::json> evaluation_from_message(const std::string& message)
{
  // calibrate.cpp: "eval {:>4}  chi2 = {:<12.6g} {}{}" with the parameters
  // "name = {:.5g} unit" joined by ", " and "  *" for the best point.
  static const std::regex line(R"(^eval +([0-9]{1,9})  chi2 = (\S+) +(.*?)( +\*)?$)");
  static const std::regex param(R"(([A-Za-z_][A-Za-z0-9_]*) = (\S+?)(?= |,|$))");
  std::smatch m;
  if (!std::regex_match(message, m, line))
    return std::nullopt;
  const auto chi2 = number_of(m[2].str());
  if (!chi2)
    return std::nullopt;
  nlohmann::json params = nlohmann::json::object();
  const std::string text = m[3].str();
  for (auto it = std::sregex_iterator(text.begin(), text.end(), param); it != std::sregex_iterator(); ++it)
  {
    const auto v = number_of((*it)[2].str());
    if (!v)
      return std::nullopt;
    params[(*it)[1].str()] = finite_or_null(*v);
  }
  return nlohmann::json{{"n", std::stol(m[1].str())},
                        {"chi2", finite_or_null(*chi2)},
                        {"params", params},
                        {"best", m[4].matched}};
}

nlohmann::json evaluations_from_history(const nlohmann::json& history)
{
  auto out = nlohmann::json::array();
  for (const auto& h : history)
    out.push_back({{"n", h.at("evaluation")},
                   {"chi2", h.at("chi2")},
                   {"params", h.value("parameters", nlohmann::json::object())},
                   {"stage", h.value("stage", "")}});
  return out;
}

nlohmann::json evaluations_after(const std::string& jsonl, long since)
{
  auto out = nlohmann::json::array();
  std::istringstream in(jsonl);
  std::string line;
  while (std::getline(in, line))
  {
    if (in.eof() && !jsonl.empty() && jsonl.back() != '\n')
      break; // the last line is still being written
    const auto j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_object() || !j.contains("n") || !j["n"].is_number_integer() || !j.contains("chi2"))
      continue;
    if (j["n"].get<long>() > since)
      out.push_back(j);
  }
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
