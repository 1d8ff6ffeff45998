// SPDX-License-Identifier: LGPL-3.0-or-later
#include "plan_drawing.hpp"
#include "half_cap.hpp"
#include "scan_landmarks.hpp"
#include <cmath>
#include <fstream>

namespace breastsim::clinic
{
namespace
{
/// Points in m rounded to 0.1 mm (what a picture can show).
nlohmann::json polyline(const std::vector<Point>& p)
{
  auto round = [](double v) { return std::round(v * 1e4) / 1e4; };
  nlohmann::json j = nlohmann::json::array();
  for (const auto& q : p)
    j.push_back({round(q[0]), round(q[1]), round(q[2])});
  return j;
}

/// The two tapes on the standing skin `s` with its nipple at `nipple`.
nlohmann::json tapes(const SkinSurface& s, const Point& notch, const Point& nipple)
{
  std::vector<Point> sn_n, n_imf;
  const double a = taut_tape(s, notch, nipple, 5e-4, &sn_n), b = nipple_to_fold(s, nipple, nullptr, &n_imf);
  return {{"sn_n", polyline(sn_n)}, {"sn_n_mm", 1e3 * a}, {"n_imf", polyline(n_imf)}, {"n_imf_mm", 1e3 * b}};
}

/// A scanned side, placed by its notch where the model's is: the scan's
/// skin, the tapes on it (SN-N from the notch, N-IMF as measured) and the
/// marking carried onto it along rays from its base centre (onto_scan).
nlohmann::json scan_drawing(const ScanSide& sc, const Point& notch, const std::vector<std::vector<Point>>& marking)
{
  const Point d{sc.notch[0] - notch[0], 0.0, sc.notch[2] - notch[2]}; // model frame + d = scan frame
  auto to_model = [&d](std::vector<Point> p)
  {
    for (auto& q : p)
      q = {q[0] - d[0], q[1] - d[1], q[2] - d[2]};
    return p;
  };
  std::vector<Point> sn_n;
  const double a = taut_tape(sc.skin.skin, sc.notch, sc.skin.nipple, 5e-4, &sn_n);
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& line : marking)
  {
    std::vector<Point> on;
    for (const auto& p : line)
      on.push_back(onto_scan(sc.skin, d, p));
    lines.push_back(polyline(on));
  }
  return {{"skin", scan_surface_json(sc.skin, d)},
          {"before",
           {{"sn_n", polyline(to_model(sn_n))}, {"sn_n_mm", 1e3 * a},
            {"n_imf", polyline(to_model(sc.measured.n_imf_path))}, {"n_imf_mm", 1e3 * sc.measured.landmarks.n_imf}}},
          {"marking", lines}};
}

SkinSurface read_surface(const std::filesystem::path& file)
{
  std::ifstream in(file);
  return skin_surface(nlohmann::json::parse(in));
}
} // namespace

nlohmann::json plan_drawing(const SideModel& m, const PlanOutcome& best, const std::filesystem::path& surgery_dir,
                            MPI_Comm comm)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0 || !best.ok)
    return nullptr;
  const SkinSurface pre = read_surface(surgery_dir / "preop" / "surface_standing.json");
  const SkinSurface post = read_surface(surgery_dir / "postop" / "surface_standing.json");
  const auto marking = wise_marking(HalfCapSpec::from(m.config), best.incision, pre);
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& line : marking)
    lines.push_back(polyline(line));
  nlohmann::json j = {{"before", tapes(pre, m.notch, m.achieved.nipple)},
                      {"after", tapes(post, m.notch, best.nipple)},
                      {"marking", lines},
                      {"new_nipple", polyline({marking.front().front()}).front()}};
  if (m.scan)
    j["scan"] = scan_drawing(*m.scan, m.notch, marking);
  return j;
}
} // namespace breastsim::clinic
