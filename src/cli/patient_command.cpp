// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim patient PATIENT.json [--case CASE] --out DIR`: a patient model
// for each breast from the clinic's landmarks (src/clinic/patient_job.hpp).
#include "command.hpp"
#include "log.hpp"
#include "option_checks.hpp"
#include "overrides.hpp"
#include "patient_job.hpp"
#include <iostream>
#include <memory>

namespace breastsim::cli
{
namespace
{
struct PatientOptions
{
  std::string patient_file, case_file;
  std::vector<std::string> sets;
  double tolerance_mm = 1.0;
  OutputOption out;
};
} // namespace

Command add_patient_command(CLI::App& root)
{
  auto o = std::make_shared<PatientOptions>();
  auto* app = root.add_subcommand("patient", "a patient model per breast from the clinic's landmarks (SN-N, N-IMF, "
                                             "base width, nipple to midline) or its standing scan; docs/CLINIC.md");
  app->add_option("patient", o->patient_file, "patient file (breastsim-patient/1 JSON; a side's scan file relative to it)")
      ->required();
  app->add_option("--case", o->case_file, "case file for the material, mesh and solver (default: every default)");
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  app->add_option("--tolerance", o->tolerance_mm, "largest landmark error accepted [mm], in [0.1, 10]")
      ->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/patient); replaced on success");
  return {app, [o]()
          {
            check_range(o->tolerance_mm, 0.1, 10, "--tolerance", "mm");
            const clinic::Patient p = clinic::read_patient(o->patient_file);
            const Config c = load_case(o->case_file, o->sets);
            std::vector<std::string> inputs{o->patient_file};
            if (!o->case_file.empty())
              inputs.push_back(o->case_file);
            const auto out = claim_output(o->out, "results/patient", inputs);
            const clinic::PatientModel m = clinic::fit_patient(c, p, 1e-3 * o->tolerance_mm, MPI_COMM_WORLD);
            clinic::write_patient_model(m, out, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << clinic::patient_table(m) << "results written to " << out.path().string()
                        << "/ (patient_model.json, case_<side>.toml, patient.txt)\n";
            return 0;
          }};
}
} // namespace breastsim::cli
