// SPDX-License-Identifier: LGPL-3.0-or-later
#include "convergence.hpp"
#include "case_options.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "mms_mixed.hpp"
#include "output.hpp"
#include "strings.hpp"

namespace breastsim
{
std::vector<int> parse_orders(const std::string& text)
{
  std::vector<int> orders;
  for (const auto& s : split_list(text))
  {
    std::size_t used = 0;
    int p = 0;
    try
    {
      p = std::stoi(s, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used != s.size())
      throw InputError("--order: not an integer: '" + s + "'");
    if (p != 1 && p != 2)
      throw InputError("--order: element order must be 1 or 2, got " + s);
    orders.push_back(p);
  }
  return orders;
}

namespace
{
/// The MMS study of each order, as JSON and tables. tissue.formulation =
/// mixed: the nearly incompressible MMS (verification/mms_mixed.hpp), the
/// mixed P2-P1 study and, on the same solution, the displacement formulation
/// at each order.
void run_mms(const Config& c, const ConvergeRequest& r, nlohmann::json& j, std::string& table,
             MPI_Comm comm)
{
  if (CaseOptions::from(c).formulation == TissueFormulation::mixed)
  {
    const double h = HalfCapSpec::from(c).mesh_size;
    IncompressibleMmsSetup setup = r.mms_incompressible;
    setup.meshes = r.mms_meshes;
    for (int k = -1; k < static_cast<int>(r.orders.size()); ++k)
    {
      const bool mixed = k < 0;
      auto s = incompressible_mms_study(c, mixed, mixed ? 2 : r.orders[k], h, r.levels, comm, setup);
      j["mms"].push_back(to_json(s));
      table += mms_table(s);
    }
    return;
  }
  for (int p : r.orders)
  {
    auto s = mms_study(c, p, HalfCapSpec::from(c).mesh_size, r.levels, comm, r.mms_meshes);
    j["mms"].push_back(to_json(s));
    table += mms_table(s);
  }
}

/// The case's studies (every order), as JSON and tables.
void run_case(const Config& c, const ConvergeRequest& r, nlohmann::json& j, std::string& table,
              MPI_Comm comm)
{
  for (const auto& s : converge_case(c, r.levels, r.orders, r.quantities, comm, r.stage, r.refine))
  {
    j["studies"].push_back(to_json(s));
    table += convergence_table(s);
  }
}
} // namespace

ConvergeReport run_convergence(const Config& c, const ConvergeRequest& r, const OutputTarget& out,
                               MPI_Comm comm)
{
  HalfCapSpec::from(c).require_parametric_cap("converge (its levels are meshes of the cap)");
  check_tissue_formulation(c);
  nlohmann::json j;
  j["case"] = CaseOptions::from(c).name;
  j["levels"] = r.levels;
  j["stage"] = r.mms ? "mms" : (r.stage == ConvergeStage::surgery ? "surgery" : "preop");
  ConvergeReport report;
  if (r.mms)
    run_mms(c, r, j, report.table, comm);
  else
    run_case(c, r, j, report.table, comm);
  OutputDir dir(out, comm);
  write_json(dir.path() / "convergence.json", j, comm);
  write_text(dir.path() / "convergence.txt", report.table, comm);
  if (log::is_root())
    report.plotted = plot_convergence(dir.path() / "convergence.json", dir.path() / "convergence.png");
  dir.commit();
  return report;
}
} // namespace breastsim
