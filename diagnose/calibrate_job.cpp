// SPDX-License-Identifier: LGPL-3.0-or-later
#include "calibrate_job.hpp"
#include "calibration_output.hpp"
#include "diagnose.hpp"
#include "diagnosis_output.hpp"
#include "log.hpp"
#include "optimizer.hpp"
#include "output.hpp"
#include "output_options.hpp"

namespace breastsim::diagnosis
{
namespace
{
/// 3D surface points: the point-to-skin fit of `diagnose`, without discovery.
std::string fit_recording(const CalibrateJob& job, const OutputTarget& out, MPI_Comm comm)
{
  const Recording& rec = *job.data.recording;
  DiagnoseOptions d;
  d.fit = job.request.fit;
  d.discover = false;
  d.ranks_per_case = job.request.ranks_per_case;
  OutputDir dir(out, comm);
  const auto res = diagnose(rec, job.start, d, comm);
  write_diagnosis(dir.path(), res, rec, comm, OutputOptions::from(job.start).pictures_on());
  write_text(dir.path() / "calibrated.toml", res.final_fit.config.to_toml(), comm);
  dir.commit();
  if (!log::is_root())
    return "";
  return report_text(res, rec) + "results written to " + out.path().string()
         + "/ (calibrated.toml, diagnosis.json, residual maps)\n";
}

std::string fit_measurements(const CalibrateJob& job, const OutputTarget& out,
                             const std::filesystem::path& checkpoint, MPI_Comm comm)
{
  const calibration::CalibrateRequest& r = job.request;
  calibration::CalibrateOptions co;
  co.optimizer.algorithm = r.algorithm;
  co.optimizer.max_evals = r.max_evals;
  co.checkpoint = checkpoint;
  co.resume = r.resume;
  co.measurements_source = r.data_file;
  co.morph = !r.remesh;
  co.correction_mesh_size = r.correction_mesh_size;
  co.ranks_per_case = r.ranks_per_case;
  co.on_evaluation = job.on_evaluation;
  log::info("calibrating [{}] with {} against {} measurements in {} postures", r.fit, r.algorithm,
            job.data.measurements.items.size(), job.data.measurements.postures.size());
  const auto res = calibration::calibrate(job.start, job.data.measurements, job.fit, co, comm);
  const bool pictures = OutputOptions::from(job.start).pictures_on();
  calibration::write_calibration(res, out, comm, {pictures, r.picture_size});
  if (!log::is_root())
    return "";
  return calibration::calibration_table(res.report) + "results written to " + out.path().string()
         + "/ (calibrated.toml for `breastsim simulate`, report.json, surface_<posture>.json"
         + (pictures ? ", misfit_history.png, measurements.png, view_<posture>.png" : "") + ")\n";
}
} // namespace

CalibrateJob prepare_calibration(const Config& start, const calibration::CalibrateRequest& r)
{
  CalibrateJob job{start, r, calibration::read_calibration_data(r.data_file), {}, {}};
  if (job.data.recording)
    return job; // the diagnosis parses --fit
  job.fit = calibration::parse_fit(r.fit, start);
  calibration::check_algorithm(r.algorithm);
  return job;
}

std::string run_calibration(const CalibrateJob& job, const OutputTarget& out,
                            const std::filesystem::path& checkpoint, MPI_Comm comm)
{
  return job.data.recording ? fit_recording(job, out, comm)
                            : fit_measurements(job, out, checkpoint, comm);
}
} // namespace breastsim::diagnosis
