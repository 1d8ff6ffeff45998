// SPDX-License-Identifier: LGPL-3.0-or-later
#include "patient_scans.hpp"
#include "errors.hpp"
#include "job_id.hpp"
#include "json_file.hpp"
#include <fmt/format.h>

namespace breastsim::app
{
namespace
{
/// {file, units} of the consultation upload `id` below `jobs`.
std::pair<std::string, std::string> uploaded(const std::filesystem::path& jobs, const std::string& id,
                                             const std::string& key)
{
  const auto folder = jobs / id;
  const auto file = folder / "request.json";
  if (!std::filesystem::is_regular_file(file))
    throw InputError(fmt::format("{} = \"{}\": no such upload (upload the scan first)", key, id));
  const auto request = calibration::read_json_file(file, "upload request");
  if (request.value("kind", "") != "scan" || !request.contains("scan") ||
      request.at("scan").value("use", "") != "consultation")
    throw InputError(fmt::format("{} = \"{}\": not a scan uploaded for the consultation", key, id));
  const auto& s = request.at("scan");
  return {(folder / s.at("file").get<std::string>()).string(), s.at("units").get<std::string>()};
}
} // namespace

nlohmann::json resolve_patient_scans(const nlohmann::json& patient, const std::filesystem::path& jobs)
{
  nlohmann::json out = patient;
  if (!out.is_object())
    return out; // refused by the patient reader, with its message
  for (const char* side : {"left", "right"})
  {
    if (!out.contains(side) || !out[side].is_object() || !out[side].contains("scan") || !out[side]["scan"].is_object())
      continue;
    auto& scan = out[side]["scan"];
    const std::string key = std::string(side) + ".scan.upload";
    for (const char* k : {"file", "units"})
      if (scan.contains(k))
        throw InputError(fmt::format("{}.scan.{}: not allowed in the app (name the upload: {}.scan.upload)", side, k,
                                     side));
    if (!scan.contains("upload") || !scan["upload"].is_string() || !is_job_id(scan["upload"].get<std::string>()))
      throw InputError(fmt::format("{} = {}: expected the id of the uploaded scan (16 hexadecimal digits)", key,
                                   scan.value("upload", nlohmann::json()).dump().substr(0, 40)));
    const std::string id = scan["upload"].get<std::string>();
    scan.erase("upload");
    if (jobs.empty())
      scan["file"] = "uploaded-scan", scan["units"] = "mm";
    else
      std::tie(scan["file"], scan["units"]) = uploaded(jobs, id, key);
  }
  return out;
}
} // namespace breastsim::app
