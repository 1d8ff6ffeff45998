// SPDX-License-Identifier: LGPL-3.0-or-later
#include "report_api.hpp"
#include "errors.hpp"
#include "http_reply.hpp"
#include "job_id.hpp"
#include "consult_report.hpp"
#include "report.hpp"
#include <cmath>
#include <fstream>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
/// Whether the surgery's case holds the calibration's fitted values (to the
/// 6 digits the page shows: |value / fitted - 1| <= 1e-5).
bool uses_fit(const JobRecord& surgery, const JobRecord& calibration)
{
  for (const auto& [key, fitted] : calibration.summary.at("fitted_overrides").items())
  {
    const auto it = surgery.overrides.find(key);
    if (it == surgery.overrides.end() || !it->is_number() ||
        std::abs(it->get<double>() / fitted.get<double>() - 1) > 1e-5)
      return false;
  }
  return true;
}

/// The finished calibration the request names ("calibration": id) and the
/// surgery used, or nothing.
std::optional<JobRecord> named_calibration(const JobStore& store, const nlohmann::json& request,
                                           const JobRecord& surgery)
{
  const auto id = request.value("calibration", nlohmann::json());
  if (id.is_null())
    return std::nullopt;
  if (!id.is_string() || !is_job_id(id.get<std::string>()))
    throw InputError("calibration: the id of a finished calibration job (16 hex digits), or null");
  auto r = store.get(id.get<std::string>());
  if (!r || r->kind != "calibrate" || r->state != JobState::done)
    throw InputError("calibration = " + id.get<std::string>() + ": no finished calibration job with this id");
  if (!uses_fit(surgery, *r))
    throw InputError("calibration = " + id.get<std::string>() +
                     ": the surgery's case does not hold this calibration's fitted values");
  return r;
}

/// `text` into `file` through a temporary sibling (readers never see half a report).
void write_atomically(const fs::path& file, const std::string& text)
{
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::trunc | std::ios::binary);
    f << text;
    if (!f.flush())
      throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, file);
}
} // namespace

void add_report_routes(httplib::Server& server, JobStore& store)
{
  server.Post(R"(/api/jobs/([0-9a-f]{16})/report)", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto job = store.get(id);
    if (!job || (job->kind != "surgery" && job->kind != "plan") || job->state != JobState::done)
      return reply_error(res, 404, "no finished surgery or plan job with this id");
    with_json_body(req, res, [&](const nlohmann::json& body) {
      const auto pictures = report_pictures(body);
      if (job->kind == "plan") // the consultation's report: for the patient and for the record
      {
        if (!body.value("calibration", nlohmann::json()).is_null())
          throw InputError("calibration: a plan's report names no calibration (its models are fitted to landmarks)");
        write_atomically(store.folder(id) / "report.html", consult_report_html(*job, pictures));
        store.update(id, [](JobRecord& r) { r.files["report.html"] = "report.html"; });
        return nlohmann::json{{"ok", true}, {"url", "/api/jobs/" + id + "/files/report.html"}};
      }
      const auto calibration = named_calibration(store, body, *job);
      write_atomically(store.folder(id) / "report.html",
                       report_html(*job, calibration ? &*calibration : nullptr, pictures));
      store.update(id, [](JobRecord& r) { r.files["report.html"] = "report.html"; });
      return nlohmann::json{{"ok", true}, {"url", "/api/jobs/" + id + "/files/report.html"}};
    });
  });
}
} // namespace breastsim::app
