// SPDX-License-Identifier: LGPL-3.0-or-later
#include "patient_job.hpp"
#include "log.hpp"
#include "on_root.hpp"
#include "scan_landmarks.hpp"
#include "output.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::clinic
{
namespace
{
/// Collective. A scanned side: its landmarks measured on the scan, the
/// model fitted to them, then its standing skin compared with the scan.
SideModel fit_scanned_side(const Config& base, const std::string& side, const SideLandmarks& entered,
                           const SideScan& in, double tolerance, MPI_Comm comm)
{
  auto sc = std::make_shared<ScanSide>();
  sc->input = in;
  sc->skin = read_scanned_skin(in);
  sc->measured = measure_scan(sc->skin, in.notch);
  const SideLandmarks target = scan_landmarks(sc->measured, entered, in.file);
  log::info("patient: fitting the {} breast to the landmarks measured on its scan (N-IMF {:.1f} cm, base width "
            "{:.1f} cm, grade {})", side, 100 * target.n_imf, 100 * target.base_width, *target.ptosis_grade);
  SideModel m = fit_side(base, side, target, tolerance, comm);
  std::array<double, 8> v{};
  on_root(comm,
          [&]
          {
            const auto c = compare_with_scan(sc->skin, sc->measured.fold, m.standing, m.achieved.fold);
            v = {c.mean, c.p95, c.max, c.volume_scan, c.volume_model, c.shift[0], c.shift[1], c.shift[2]};
          });
  MPI_Bcast(v.data(), static_cast<int>(v.size()), MPI_DOUBLE, 0, comm);
  sc->comparison = {v[0], v[1], v[2], v[3], v[4], {v[5], v[6], v[7]}};
  if (sc->measured.notch)
    sc->notch = *sc->measured.notch;
  else // on the scan as on the model: the taut tape over the scan has the entered SN-N
    sc->notch = {sc->skin.nipple[0] - target.nipple_midline, 0.0,
                 place_notch(sc->skin.skin, sc->skin.nipple, target.nipple_midline, target.sn_n, comm)};
  m.scan = sc;
  return m;
}
} // namespace

PatientModel fit_patient(const Config& base, const Patient& p, double tolerance, MPI_Comm comm)
{
  PatientModel m{p.id, {}, tolerance, p.body};
  for (const auto& [side, landmarks] : p.sides)
  {
    if (const auto sc = p.scans.find(side); sc != p.scans.end())
    {
      m.sides.push_back(fit_scanned_side(base, side, landmarks, sc->second, tolerance, comm));
      continue;
    }
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
  std::string t = fmt::format("patient {}: landmarks standing, entered (or measured on a scan) -> simulated [cm]\n", m.id.empty() ? "-" : m.id);
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
    if (s.scan)
    {
      const auto& c = s.scan->comparison;
      t += fmt::format("{}: landmarks measured on the scan {}; the model's standing skin lies {:.1f} mm (mean; 95 % "
                       "within {:.1f} mm, at most {:.1f} mm) from the scan's, volume {:.0f} cm^3 against the scan's "
                       "{:.0f} cm^3 ({:+.0f} %)\n",
                       s.side, s.scan->input.file.filename().string(), 1e3 * c.mean, 1e3 * c.p95, 1e3 * c.max,
                       1e6 * c.volume_model, 1e6 * c.volume_scan, 100 * c.volume_error());
    }
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
