#include "diagnosis_output.hpp"
#include "output.hpp"
#include "viewer.hpp"
#include <fmt/format.h>

namespace breastsim::calibration
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

std::vector<double> mm(const std::vector<double>& v)
{
  std::vector<double> out;
  for (double x : v)
    out.push_back(1e3 * x);
  return out;
}
} // namespace

void write_diagnosis(const std::filesystem::path& dir, const Diagnosis& d, const Recording& rec,
                     MPI_Comm comm)
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
  run_viewer_script("diagnose_plots.py", {dir.string()}, "residual maps of " + dir.string(), comm);
}
} // namespace breastsim::calibration
