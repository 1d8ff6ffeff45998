// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// `breastsim patient`: a patient model for each entered breast from its
// landmarks (patient_fit.hpp), written as one folder: patient_model.json
// (targets, achieved landmarks, fitted values, the notch in each breast's
// frame), case_<side>.toml (a complete case for simulate, surgery and plan)
// and patient.txt (the table printed).
#include "output_target.hpp"
#include "patient_fit.hpp"

namespace breastsim::clinic
{
struct PatientModel
{
  std::string id;
  std::vector<SideModel> sides;
  double tolerance = 0; ///< the largest landmark error accepted [m]
  std::optional<Body> body;
};

/// Collective. Fit every side of `p` on the case `base`; InputError when a
/// side cannot be reached within `tolerance` [m].
PatientModel fit_patient(const Config& base, const Patient& p, double tolerance, MPI_Comm comm);
/// Collective. Write the patient model into `out` (replaced only on success).
void write_patient_model(const PatientModel& m, const OutputTarget& out, MPI_Comm comm);
/// Per side the entered and the simulated landmarks, in cm, and the fit.
std::string patient_table(const PatientModel& m);
nlohmann::json to_json(const PatientModel& m);
} // namespace breastsim::clinic
