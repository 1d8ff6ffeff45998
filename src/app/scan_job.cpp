// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_job.hpp"
#include "case_request.hpp"
#include "config.hpp"
#include "errors.hpp"
#include "full_breast_surgery.hpp"
#include "job_request.hpp"
#include "neutral_state.hpp"
#include "posture.hpp"
#include "scan_model_job.hpp"
#include "scan_readers.hpp"
#include "simulate.hpp"
#include <mpi.h>
#include <string>
#include <vector>

namespace breastsim::app
{
namespace fs = std::filesystem;

void run_scan_job(const fs::path& folder, const nlohmann::json& request, const OutputRules& rules,
                  const Progress& progress)
{
  const auto& scan = request.at("scan");
  if (scan.value("use", "model") == "consultation") // kept for a patient's model (patient_scans.hpp), checked on upload
    return progress.report("scan kept for the consultation", 1);
  ScanModelRequest r;
  r.skin = folder / scan.at("file").get<std::string>();
  r.options.units = scan::parse_units(scan.at("units").get<std::string>(), "units");
  r.options.mesh.mesh_size = scan.at("mesh_size").get<double>(); // 0: by the breast's volume
  r.posture = named_posture(scan.at("posture").get<std::string>());
  OutputRules inputs = rules;
  inputs.inputs.push_back(r.skin);
  progress.report("scan model: fit and mesh of the skin", 0);
  scan_model(r, OutputTarget::claim((folder / "model").string(), inputs, MPI_COMM_WORLD), MPI_COMM_WORLD);

  progress.report("neutral state: the stress-free breast of the scan", 0.3);
  const Config loaded = Config::from_file(folder / "model" / "case.toml");
  neutral_state(loaded, r.posture, InverseOptions{},
                OutputTarget::claim((folder / "neutral").string(), rules, MPI_COMM_WORLD), MPI_COMM_WORLD);

  Config neutral = Config::from_file(folder / "neutral" / "case.reference.toml");
  neutral.set("postures.names", std::vector<std::string>(std::begin(scan_postures), std::end(scan_postures)));
  neutral.validate();
  simulate(neutral, OutputTarget::claim((folder / "result").string(), rules, MPI_COMM_WORLD), MPI_COMM_WORLD,
           progress.part(0.6, 1.0, "simulate: "));
}

void run_scan_surgery(const fs::path& scan_folder, const nlohmann::json& request, const OutputTarget& out,
                      const Progress& progress)
{
  Config c = Config::from_file(scan_folder / scan_neutral_case);
  const Config given = case_from_overrides(request.at("overrides")); // each value parsed as --set parses it
  for (const auto& [key, _] : request.at("overrides").items())
  {
    if (!is_scan_surgery_key(key))
      throw InputError("key '" + key + "' is not applied to the surgery of a scanned breast");
    c.set(key, given.values().at(key));
  }
  c.validate();
  full_breast_surgery(c, out, MPI_COMM_WORLD, progress);
}
} // namespace breastsim::app
