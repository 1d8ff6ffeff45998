// SPDX-License-Identifier: LGPL-3.0-or-later
#include "plan_drawing.hpp"
#include "half_cap.hpp"
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
  return {{"before", tapes(pre, m.notch, m.achieved.nipple)},
          {"after", tapes(post, m.notch, best.nipple)},
          {"marking", lines},
          {"new_nipple", polyline({marking.front().front()}).front()}};
}
} // namespace breastsim::clinic
