// SPDX-License-Identifier: LGPL-3.0-or-later
#include "diagnosis_output.hpp"
#include "geometry_options.hpp"
#include "diagnose.hpp"
#include "field_discovery.hpp"
#include "field_term_writer.hpp"
#include "law_discovery.hpp"
#include "log.hpp"
#include "output.hpp"
#include "output_options.hpp"
#include "viewer.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::diagnosis
{
namespace
{
/// A point cloud with per-point attributes as XDMF (inline XML data).
std::string xdmf_points(const std::vector<Point>& pts,
                        const std::vector<std::pair<std::string, std::vector<double>>>& fields)
{
  const std::size_t n = pts.size();
  std::string s = "<?xml version=\"1.0\"?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
                  "<Grid Name=\"recording\" GridType=\"Uniform\">\n";
  s += fmt::format("<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
                   "NodesPerElement=\"1\"/>\n",
                   n);
  s += fmt::format("<Geometry GeometryType=\"XYZ\">\n<DataItem Dimensions=\"{} 3\" "
                   "NumberType=\"Float\" Precision=\"8\" Format=\"XML\">\n",
                   n);
  for (const auto& p : pts)
    s += fmt::format("{:.9g} {:.9g} {:.9g}\n", p[0], p[1], p[2]);
  s += "</DataItem>\n</Geometry>\n";
  for (const auto& [name, v] : fields)
  {
    s += fmt::format("<Attribute Name=\"{}\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                     "<DataItem Dimensions=\"{}\" NumberType=\"Float\" Precision=\"8\" "
                     "Format=\"XML\">\n",
                     name, n);
    for (double x : v)
      s += fmt::format("{:.6g}\n", x);
    s += "</DataItem>\n</Attribute>\n";
  }
  return s + "</Grid>\n</Domain>\n</Xdmf>\n";
}

/// |residual| at the surface's vertices [mm]: inverse-distance mean over
/// the k nearest recorded points (for colouring the 3D page).
std::vector<double> vertex_field(const nlohmann::json& surface, const std::vector<Point>& pts,
                                 const std::vector<double>& residual)
{
  const auto& v = surface.at("vertices");
  const std::size_t k = std::min<std::size_t>(6, pts.size());
  std::vector<double> out;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3)
  {
    const Point x = {v[i].get<double>(), v[i + 1].get<double>(), v[i + 2].get<double>()};
    std::vector<std::pair<double, std::size_t>> d;
    for (std::size_t j = 0; j < pts.size(); ++j)
      d.push_back({std::pow(x[0] - pts[j][0], 2) + std::pow(x[1] - pts[j][1], 2)
                       + std::pow(x[2] - pts[j][2], 2),
                   j});
    std::partial_sort(d.begin(), d.begin() + k, d.end());
    double num = 0, den = 0;
    for (std::size_t m = 0; m < k; ++m)
    {
      const double w = 1.0 / (std::sqrt(d[m].first) + 1e-4); // 0.1 mm floor
      num += w * std::abs(residual[d[m].second]);
      den += w;
    }
    out.push_back(std::round(1e7 * num / den) / 1e4); // mm, 0.1 um
  }
  return out;
}

std::vector<double> mm(const std::vector<double>& v)
{
  std::vector<double> out;
  for (double x : v)
    out.push_back(1e3 * x);
  return out;
}
} // namespace

void write_diagnosis(const std::filesystem::path& dir, const Diagnosis& d, const Recording& rec,
                     MPI_Comm comm, bool pictures)
{
  write_json(dir / "diagnosis.json", to_json(d, rec), comm);
  write_text(dir / "diagnosis.txt", report_text(d, rec), comm);
  const FitState& before = d.rounds.front().before;
  const FitState& after = d.final_fit;
  nlohmann::json res;
  res["noise_sigma_mm"] = 1e3 * d.noise_sigma;
  res["discovered"] = d.discovered;
  res["postures"] = nlohmann::json::array();
  for (std::size_t p = 0; p < rec.postures.size(); ++p)
  {
    const auto& P = rec.postures[p];
    res["postures"].push_back({{"name", P.name},
                               {"theta_deg", P.theta_deg},
                               {"points_mm", [&] {
                                  std::vector<std::array<double, 3>> v;
                                  for (const auto& x : P.points)
                                    v.push_back({1e3 * x[0], 1e3 * x[1], 1e3 * x[2]});
                                  return v;
                                }()},
                               {"before_mm", mm(before.distances[p])},
                               {"after_mm", mm(after.distances[p])},
                               {"rms_before_mm", 1e3 * before.rms[p]},
                               {"rms_after_mm", 1e3 * after.rms[p]}});
    write_text(dir / ("residuals_" + P.name + ".xdmf"),
               xdmf_points(P.points, {{"residual_before_mm", mm(before.distances[p])},
                                      {"residual_after_mm", mm(after.distances[p])}}),
               comm);
  }
  write_json(dir / "residuals.json", res, comm);
  write_text(dir / "case.diagnosed.toml", after.config.to_toml(), comm);
  if (d.field && d.field->accepted)
  {
    write_text(dir / "case.field.toml", d.field->after.config.to_toml(), comm);
    write_text(dir / "found_stiffness.py",
               field_term_source(*d.field, "found_stiffness",
                                 std::filesystem::path(rec.source).filename().string()),
               comm);
  }
  if (d.law && d.law->accepted)
  {
    write_text(dir / "case.law.toml", d.law->after.config.to_toml(), comm);
    write_text(dir / "found_law.py",
               law_term_source(*d.law, "found_law", std::filesystem::path(rec.source).filename().string()),
               comm);
  }
  if (pictures)
    run_viewer_script("diagnose_plots.py", {dir.string()}, "residual maps of " + dir.string(), comm);
  // The final model's skin with |residual| fields: breast pictures and the 3D page.
  int rank;
  MPI_Comm_rank(comm, &rank);
  for (std::size_t p = 0; p < rec.postures.size() && p < d.surfaces.size(); ++p)
  {
    std::string text;
    if (rank == 0)
    {
      nlohmann::json s = d.surfaces[p];
      s["fields"]["abs_residual_before_mm"]
          = vertex_field(s, rec.postures[p].points, before.distances[p]);
      s["fields"]["abs_residual_after_mm"] = vertex_field(s, rec.postures[p].points, after.distances[p]);
      text = s.dump() + "\n";
    }
    write_text(dir / ("surface_" + rec.postures[p].name + ".json"), text, comm);
  }
  if (!pictures)
    return;
  render_pictures(dir, {}, comm);
  write_view_page(dir, {}, comm);
}

std::string run_diagnosis(const Recording& rec, const Config& current, const DiagnoseOptions& o,
                          const OutputTarget& out, MPI_Comm comm)
{
  HalfCapSpec::from(current).require_parametric_cap(
      "diagnose (its numerical noise floor solves on a finer mesh of the cap)");
  OutputDir dir(out, comm);
  const auto d = diagnose(rec, current, o, comm);
  const bool pictures = OutputOptions::from(current).pictures_on();
  write_diagnosis(dir.path(), d, rec, comm, pictures);
  dir.commit();
  if (!log::is_root())
    return "";
  return report_text(d, rec) + "results written to " + out.path().string()
         + "/ (diagnosis.json, diagnosis.txt, residuals, case.diagnosed.toml"
         + (pictures ? ", residual maps, pictures, index.html" : "") + ")\n";
}
} // namespace breastsim::diagnosis
