// SPDX-License-Identifier: LGPL-3.0-or-later
#include "patient_job.hpp"
#include "log.hpp"
#include "output.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::clinic
{
PatientModel fit_patient(const Config& base, const Patient& p, double tolerance, MPI_Comm comm)
{
  PatientModel m{p.id, {}, tolerance, p.body};
  for (const auto& [side, landmarks] : p.sides)
  {
    log::info("patient: fitting the {} breast to its landmarks", side);
    m.sides.push_back(fit_side(base, side, landmarks, tolerance, comm));
  }
  return m;
}

nlohmann::json to_json(const PatientModel& m)
{
  nlohmann::json sides = nlohmann::json::array();
  for (const auto& s : m.sides)
    sides.push_back(to_json(s));
  nlohmann::json j = {{"format", "breastsim-patient-model/1"}, {"id", m.id}, {"tolerance_mm", 1e3 * m.tolerance},
                      {"sides", sides}};
  if (m.body)
    j["body"] = to_json(*m.body);
  return j;
}

std::string patient_table(const PatientModel& m)
{
  std::string t = fmt::format("patient {}: landmarks standing, entered -> simulated [cm]\n", m.id.empty() ? "-" : m.id);
  t += fmt::format("{:<7} {:>15} {:>15} {:>15} {:>15} {:>15} {:>8}\n", "side", "SN-N", "N-IMF", "base width",
                   "to midline", "projection", "ptosis");
  auto cell = [](double entered, double simulated)
  { return fmt::format("{:>6.1f} -> {:<5.1f}", 100 * entered, 100 * simulated); };
  for (const auto& s : m.sides)
  {
    const auto& a = s.achieved.landmarks;
    const std::string proj = s.target.projection ? cell(*s.target.projection, *a.projection)
                                                 : fmt::format("{:>6} -> {:<5.1f}", "-", 100 * *a.projection);
    const std::string ptosis = s.target.ptosis_grade ? fmt::format("{} -> {}", *s.target.ptosis_grade, s.achieved.ptosis_grade)
                                                     : fmt::format("- -> {}", s.achieved.ptosis_grade);
    t += fmt::format("{:<7} {} {} {} {} {} {:>8}\n", s.side, cell(s.target.sn_n, a.sn_n), cell(s.target.n_imf, a.n_imf),
                     cell(s.target.base_width, a.base_width), cell(s.target.nipple_midline, a.nipple_midline), proj,
                     ptosis);
  }
  for (const auto& s : m.sides)
  {
    t += fmt::format("{}: largest landmark error {:.2f} mm (accepted {:.1f} mm); cap R = {:.1f} mm, H = {:.1f} mm, "
                     "stiffness x {:.3g}{}; {} iteration(s), {} standing solves\n",
                     s.side, 1e3 * s.largest_error, 1e3 * m.tolerance, 1e3 * s.config.number("geometry.R"),
                     1e3 * s.config.number("geometry.H"), s.stiffness_factor,
                     s.target.ptosis_grade ? " (fitted to the ptosis grade)" : " (the case's moduli)", s.iterations, s.solves);
    for (const auto& n : s.notes)
      t += fmt::format("{}: note: {}\n", s.side, n);
  }
  if (m.body)
  {
    const auto& b = *m.body;
    t += "body:";
    if (b.height)
      t += fmt::format(" height {:.0f} cm", 100 * *b.height);
    if (b.weight_kg)
      t += fmt::format(", weight {:.0f} kg", *b.weight_kg);
    if (const auto a = b.surface_area())
      t += fmt::format(", body surface area {:.2f} m^2 (Mosteller)", *a);
    if (!b.bra_size.empty())
      t += ", bra " + b.bra_size;
    t += "\n";
  }
  return t;
}

void write_patient_model(const PatientModel& m, const OutputTarget& out, MPI_Comm comm)
{
  OutputDir dir(out, comm);
  write_json(dir.path() / "patient_model.json", to_json(m), comm);
  for (const auto& s : m.sides)
    write_text(dir.path() / ("case_" + s.side + ".toml"), s.config.to_toml(), comm);
  write_text(dir.path() / "patient.txt", patient_table(m), comm);
  dir.commit();
}
} // namespace breastsim::clinic
