// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_request.hpp"
#include "patient_scans.hpp"
#include "case_request.hpp"
#include "errors.hpp"
#include "fit_parameters.hpp"
#include "job_id.hpp"
#include "landmarks.hpp"
#include "measurements.hpp"
#include "plan_job.hpp"
#include "plan_targets.hpp"
#include "plan_api.hpp"
#include "recording_api.hpp"
#include "sweep_request.hpp"
#include <set>

namespace breastsim::app
{
namespace
{
void check_fields(const nlohmann::json& body, const std::set<std::string>& allowed, const std::string& kind)
{
  std::string names;
  for (const auto& a : allowed)
    names += (names.empty() ? "" : ", ") + a;
  for (const auto& [k, _] : body.items())
    if (!allowed.count(k))
      throw InputError("field '" + k + "' is not allowed in a " + kind + " job request (allowed: " + names + ")");
}

void check_calibration(nlohmann::json& request)
{
  const Config start = case_from_overrides(request["overrides"]);
  // The data: point measurements or a 3D surface recording, as `calibrate` reads them.
  if (request.contains("measurements") == request.contains("recording"))
    throw InputError("give one of the fields 'measurements' (the measurement document to fit) or "
                     "'recording' (a 3D surface recording, breastsim-recording/1)");
  if (request.contains("recording"))
    check_recording(request["recording"]);
  else
    calibration::parse_measurements(request["measurements"], "measurements");
  if (!request.contains("fit"))
    request["fit"] = calibration::CalibrateRequest{}.fit;
  if (!request["fit"].is_string())
    throw InputError("fit = " + request["fit"].dump().substr(0, 40) + ": expected names such as \"mu,c\"");
  calibration::parse_fit(request["fit"], start);
  if (!request.contains("max_evals"))
    request["max_evals"] = calibration::CalibrateRequest{}.max_evals;
  const auto& m = request["max_evals"];
  if (!m.is_number_integer() || m.get<long>() < 1 || m.get<long>() > 5000)
    throw InputError("max_evals = " + m.dump().substr(0, 40) + " is out of range: allowed [1, 5000]");
  calibration::check_calibrate_request(calibrate_request(request, ""), start);
}

/// A surgery on a scan's breast: "scan" names the scan job; the overrides
/// may set the plan (incision.*), the postures and the surgery's own keys,
/// applied to the scan's neutral case; the incision is checked on the
/// scanned skin by the job (full_breast_surgery's messages).
void check_scan_surgery(const nlohmann::json& request)
{
  const auto& scan = request["scan"];
  if (!scan.is_string() || !is_job_id(scan.get<std::string>()))
    throw InputError("scan = " + scan.dump().substr(0, 40) + ": expected the id of a finished scan job "
                     "(16 hexadecimal digits)");
  case_from_overrides(request["overrides"]);
  for (const auto& [key, _] : request["overrides"].items())
    if (!is_scan_surgery_key(key))
      throw InputError("key '" + key + "' is not applied to the surgery of a scanned breast (its case is the "
                       "scan's neutral case): allowed incision.*, postures.*, surgery.*");
}
/// A patient model (and a plan): the landmarks as `patient` reads them, the
/// tolerance, and for a plan the targets as `plan` checks them.
void check_patient(nlohmann::json& request, bool plan)
{
  const Config c = case_from_overrides(request["overrides"]);
  if (!request.contains("patient"))
    throw InputError("field 'patient' is missing: the landmarks, a breastsim-patient/1 document");
  const clinic::Patient p = clinic::patient_from_json(resolve_patient_scans(request["patient"], {}), "patient");
  if (!request.contains("tolerance_mm"))
    request["tolerance_mm"] = 1.0;
  const auto& tol = request["tolerance_mm"];
  if (!tol.is_number() || !(tol.get<double>() >= 0.1 && tol.get<double>() <= 10))
    throw InputError("tolerance_mm = " + tol.dump().substr(0, 40) + " is out of range: allowed [0.1, 10] mm");
  if (!plan)
    return;
  if (!request.contains("symmetric"))
    request["symmetric"] = false;
  if (!request["symmetric"].is_boolean())
    throw InputError("symmetric = " + request["symmetric"].dump().substr(0, 40) + ": expected true or false");
  clinic::check_plan_request(c, p, clinic::targets_from_json(request.value("targets", nlohmann::json())));
}
} // namespace

bool is_scan_surgery_key(const std::string& key)
{
  return key.rfind("incision.", 0) == 0 || key.rfind("postures.", 0) == 0 || key.rfind("surgery.", 0) == 0;
}

nlohmann::json checked_job_request(const nlohmann::json& body)
{
  if (!body.is_object())
    throw InputError("the job request must be a JSON object {\"kind\": ..., \"overrides\": {...}}");
  const auto kind = body.value("kind", nlohmann::json());
  if (kind != "simulate" && kind != "surgery" && kind != "calibrate" && kind != "sweep" && kind != "patient" &&
      kind != "plan")
    throw InputError("kind = " + kind.dump().substr(0, 40) +
                     ": allowed simulate, surgery, calibrate, sweep, patient, plan");
  nlohmann::json request = body;
  if (!request.contains("overrides"))
    request["overrides"] = nlohmann::json::object();
  if (kind == "calibrate")
  {
    check_fields(body, {"kind", "overrides", "measurements", "recording", "fit", "max_evals"}, "calibrate");
    check_calibration(request);
    return request;
  }
  if (kind == "patient" || kind == "plan")
  {
    check_fields(body,
                 kind == "plan" ? std::set<std::string>{"kind", "overrides", "patient", "tolerance_mm", "targets",
                                                        "symmetric"}
                                : std::set<std::string>{"kind", "overrides", "patient", "tolerance_mm"},
                 kind);
    check_patient(request, kind == "plan");
    return request;
  }
  if (kind == "sweep")
  {
    check_fields(body, {"kind", "overrides", "vary"}, "sweep");
    incision_document(request["overrides"]); // the plan swept around must exist
    sweep_grid(request.value("vary", nlohmann::json()), case_from_overrides(request["overrides"]));
    return request;
  }
  if (kind == "surgery" && body.contains("scan"))
  {
    check_fields(body, {"kind", "overrides", "scan"}, "surgery");
    check_scan_surgery(request);
    return request;
  }
  check_fields(body, {"kind", "overrides"}, kind);
  if (kind == "surgery")
    incision_document(request["overrides"]); // an impossible incision is refused before any job
  else
    case_from_overrides(request["overrides"]);
  return request;
}

calibration::CalibrateRequest calibrate_request(const nlohmann::json& request,
                                                const std::filesystem::path& data_file)
{
  calibration::CalibrateRequest r;
  r.data_file = data_file.string();
  r.fit = request.at("fit").get<std::string>();
  r.max_evals = request.at("max_evals").get<int>();
  return r;
}
} // namespace breastsim::app
