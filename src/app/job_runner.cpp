// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_runner.hpp"
#include "calibrate_job.hpp"
#include "case_request.hpp"
#include "data_folder.hpp"
#include "errors.hpp"
#include "job_evaluations.hpp"
#include "job_id.hpp"
#include "job_request.hpp"
#include "plan_job.hpp"
#include "plan_targets.hpp"
#include "progress_channel.hpp"
#include "patient_scans.hpp"
#include "scan_job.hpp"
#include "simulate.hpp"
#include "surgery.hpp"
#include "sweep_request.hpp"
#include <csignal>
#include <fstream>
#include <mutex>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>
#include <sys/prctl.h>
#include <unistd.h>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
void write_outcome(const fs::path& folder, const nlohmann::json& outcome)
{
  std::ofstream f(folder / "outcome.json.tmp", std::ios::trunc);
  f << outcome.dump(2) << "\n";
  f.close();
  fs::rename(folder / "outcome.json.tmp", folder / "outcome.json");
}

/// The library's log lines (info and above) into log.txt, flushed at once.
void log_into(const fs::path& file)
{
  auto logger = std::make_shared<spdlog::logger>(
      "job", std::make_shared<spdlog::sinks::basic_file_sink_mt>(file.string()));
  logger->set_pattern("[%H:%M:%S] %v");
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::info);
}

/// A calibration: the measurements (or the recording) into the job's own
/// measurements.json (recording.json), then the library's calibrate job
/// with its checkpoint in the job folder.
void calibrate(const fs::path& folder, const nlohmann::json& request, const Config& c, OutputRules rules)
{
  const bool recording = request.contains("recording");
  const fs::path data = folder / (recording ? "recording.json" : "measurements.json");
  {
    std::ofstream f(data, std::ios::trunc);
    f << request.at(recording ? "recording" : "measurements").dump(2) << "\n";
  }
  const auto r = calibrate_request(request, data);
  calibration::check_calibrate_request(r, c);
  auto job = diagnosis::prepare_calibration(c, r);
  // The progress channel: each evaluation's history entry, as it is made.
  job.on_evaluation = [&folder](const nlohmann::json& h)
  { append_evaluation(folder, evaluations_from_history(nlohmann::json::array({h})).at(0)); };
  rules.inputs.push_back(data);
  const auto target = OutputTarget::claim((folder / "result").string(), rules, MPI_COMM_WORLD);
  diagnosis::run_calibration(job, target, folder / "checkpoint.json", MPI_COMM_WORLD);
  // The report's history (the same entries) is the final list.
  std::ifstream report(folder / "result" / "report.json");
  const auto rep = nlohmann::json::parse(report, nullptr, false);
  if (rep.is_object() && rep.contains("history"))
    write_evaluations(folder, evaluations_from_history(rep["history"]));
}

void run(const fs::path& folder)
{
  std::ifstream f(folder / "request.json");
  const auto request = nlohmann::json::parse(f);
  const Config c = case_from_overrides(request.at("overrides"));
  OutputRules rules;
  rules.inputs = {folder / "request.json"};
  const std::string kind = request.at("kind");
  if (kind == "calibrate")
    return calibrate(folder, request, c, rules);
  if (kind == "scan")
    return run_scan_job(folder, request, rules, progress_into(folder));
  const auto target = OutputTarget::claim((folder / "result").string(), rules, MPI_COMM_WORLD);
  const Progress progress = progress_into(folder); // the structured progress channel
  if (kind == "surgery" && request.contains("scan")) // the scan job's folder beside this one
  {
    if (!is_job_id(request.at("scan").get<std::string>()))
      throw InputError("scan: not a job id");
    run_scan_surgery(folder.parent_path() / request.at("scan").get<std::string>(), request, target, progress);
  }
  else if (kind == "surgery")
    surgery(c, target, MPI_COMM_WORLD, progress);
  else if (kind == "simulate")
    simulate(c, target, MPI_COMM_WORLD, progress);
  else if (kind == "sweep")
    sweep(c, sweep_grid(request.at("vary"), c), target, MPI_COMM_WORLD, 0, progress);
  else if (kind == "patient" || kind == "plan")
  {
    const clinic::Patient p =
        clinic::patient_from_json(resolve_patient_scans(request.at("patient"), folder.parent_path()), "patient");
    const double tol = 1e-3 * request.at("tolerance_mm").get<double>();
    if (kind == "patient")
      clinic::write_patient_model(clinic::fit_patient(c, p, tol, MPI_COMM_WORLD), target, MPI_COMM_WORLD);
    else
      clinic::plan_patient(c, p, tol, clinic::targets_from_json(request.at("targets")),
                           request.at("symmetric").get<bool>(), target, MPI_COMM_WORLD);
  }
  else
    throw InputError("kind = \"" + kind + "\": allowed simulate, surgery, calibrate, sweep, scan, patient, plan");
}
} // namespace

/// Only a job folder of a server's data folder: <data>/jobs/<id>/ with the
/// data folder's marker and the server's job.json and request.json.
void check_job_folder(const fs::path& folder)
{
  const fs::path data = folder.parent_path().parent_path();
  if (!is_job_id(folder.filename().string()) || folder.parent_path().filename() != "jobs" ||
      !fs::exists(data / data_marker) || !fs::exists(folder / "job.json") ||
      !fs::exists(folder / "request.json"))
    throw InputError("--run-job " + folder.string() + ": not a job folder of breastsim serve "
                     "(<data>/jobs/<id>/ with job.json and request.json)");
}

int run_job(const fs::path& given)
{
  const fs::path folder = normalise_path(given.string(), "--run-job");
  check_job_folder(folder); // before anything is written
  const pid_t server = getppid();
  prctl(PR_SET_PDEATHSIG, SIGTERM); // the server's end ends this job
  if (getppid() != server)
    return 1;
  log_into(folder / "log.txt");
  try
  {
    run(folder);
    write_outcome(folder, {{"ok", true}});
    return 0;
  }
  catch (const InputError& e)
  {
    write_outcome(folder, {{"ok", false}, {"error_kind", "input"}, {"error", e.what()}});
    return 2;
  }
  catch (const SolveError& e)
  {
    write_outcome(folder, {{"ok", false}, {"error_kind", "solve"}, {"error", e.what()}});
    return 3;
  }
  catch (const std::exception& e)
  {
    write_outcome(folder, {{"ok", false}, {"error_kind", "error"}, {"error", e.what()}});
    return 1;
  }
}
} // namespace breastsim::app
