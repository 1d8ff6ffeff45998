// SPDX-License-Identifier: LGPL-3.0-or-later
#include "consult_report.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::app
{
namespace
{
using json = nlohmann::json;

const json* side_of(const json& list, const std::string& side)
{
  for (const auto& s : list)
    if (s.at("side") == side)
      return &s;
  return nullptr;
}

/// Volume of the neutral cap, full breast [cm^3]: pi H (3 R^2 + H^2) / 6.
double cap_volume_cm3(const json& m)
{
  const double R = m.at("R_m"), H = m.at("H_m");
  return 1e6 * M_PI * H * (3 * R * R + H * H) / 6;
}

std::string cm(double mm)
{
  return fmt::format("{:.1f} cm", mm / 10);
}

/// The targets of a plan in words: "SN-N 215.0 mm, N-IMF 70.0 mm, 150 g, lower pole 0.55".
std::string targets_text(const json& t)
{
  std::string s;
  auto add = [&](const std::string& part) { s += (s.empty() ? "" : ", ") + part; };
  if (t.contains("sn_n_mm"))
    add(fmt::format("SN-N {:.1f} mm", t.at("sn_n_mm").get<double>()));
  if (t.contains("n_imf_mm"))
    add(fmt::format("N-IMF {:.1f} mm", t.at("n_imf_mm").get<double>()));
  if (t.contains("resection_g"))
    add(fmt::format("{:.0f} g", t.at("resection_g").get<double>()));
  if (t.contains("lower_pole_share"))
    add(fmt::format("lower pole {:.2f}", t.at("lower_pole_share").get<double>()));
  return s.empty() ? "none" : s;
}

/// For a breast measured on its scan: how close the model comes to the scan, in plain words.
std::string scanned_breast(const json& model)
{
  if (!model.contains("scan"))
    return "";
  const auto& sc = model.at("scan");
  return fmt::format("<p class=\"keep\" data-key=\"scan-note\">This breast was measured on its 3D scan. The computer "
                     "model's surface lies on average {:.1f} cm from the scanned surface, and the model holds {:.0f} "
                     "cm³ where the scan holds {:.0f} cm³.</p>",
                     sc.at("model_to_scan_mm").at("mean").get<double>() / 10, sc.at("volume_cm3").at("model").get<double>(),
                     sc.at("volume_cm3").at("scan").get<double>());
}

/// The patient's lines for one breast, in plain words.
std::string patient_breast(const std::string& side, const json& model, const json& plan)
{
  const auto& p = plan.at("plan");
  if (!p.at("ok").get<bool>())
    return fmt::format("<h2>Your {} breast</h2><p>No plan could be made for this breast.</p>", side);
  const auto& before = model.at("achieved");
  const auto& post = p.at("post_standing");
  const double notch_z = model.at("notch_m")[2], z0 = model.at("nipple_standing_m")[2], z1 = post.at("nipple_m")[2];
  return fmt::format(
      "<h2>Your {0} breast</h2><table class=\"keep\"><tr><th></th><th>now</th><th>after surgery</th></tr>"
      "<tr><td>Tissue removed</td><td></td><td><b data-key=\"{0}-grams\">{1:.0f} g</b></td></tr>"
      "<tr><td>Breast volume</td><td>{2:.0f} cm³</td><td>{3:.0f} cm³</td></tr>"
      "<tr><td>Nipple, measured from the notch at the base of the neck</td><td>{4}</td><td>{5}</td></tr>"
      "<tr><td>Nipple, its height below the notch</td><td>{6:.1f} cm</td><td>{7:.1f} cm</td></tr>"
      "<tr><td>Nipple to the fold under the breast</td><td>{8}</td><td>{9}</td></tr></table>"
      "<p class=\"keep\">The nipple is planned to sit <b>{10:.1f} cm higher</b>, standing.</p>{11}",
      side, p.at("surgical").at("resection_g").get<double>(), cap_volume_cm3(model), p.at("volume_post_cm3").get<double>(),
      cm(before.at("sn_n_mm")), cm(post.at("sn_n_mm")), 100 * (notch_z - z0), 100 * (notch_z - z1),
      cm(before.at("n_imf_mm")), cm(post.at("n_imf_mm")), 100 * (z1 - z0), scanned_breast(model));
}

/// Both breasts after surgery, side by side, in plain words.
std::string symmetry(const json& models, const json& plans)
{
  const json *l = side_of(plans, "left"), *r = side_of(plans, "right");
  if (!l || !r || !l->at("plan").at("ok").get<bool>() || !r->at("plan").at("ok").get<bool>())
    return "";
  const auto &pl = l->at("plan"), &pr = r->at("plan");
  const double zl = side_of(models, "left")->at("notch_m")[2].get<double>() - pl.at("post_standing").at("nipple_m")[2].get<double>();
  const double zr = side_of(models, "right")->at("notch_m")[2].get<double>() - pr.at("post_standing").at("nipple_m")[2].get<double>();
  const double vl = pl.at("volume_post_cm3"), vr = pr.at("volume_post_cm3");
  return fmt::format("<h2>Both breasts after surgery</h2><p class=\"keep\">The nipples are planned {:.1f} cm apart in "
                     "height, and the breasts' volumes {:.0f} % apart ({:.0f} and {:.0f} cm³).</p>",
                     100 * std::abs(zl - zr), 200 * std::abs(vl - vr) / (vl + vr), vl, vr);
}

const char* const limits = R"(<h2>What this simulation cannot tell you</h2><ul class="keep">
<li>It is a computer model of your breasts fitted to a few measurements taken with a tape; it has not yet
been compared with the results of real operations, and its breast is simpler than yours: on test breasts of
other shapes its surface was about half a centimetre off on average, and it held up to a quarter less volume
where the breast was fuller below or to the side.</li>
<li>How your scars will heal, swelling and how the breasts settle over the months after surgery.</li>
<li>Sensation, breastfeeding and the risks of the operation.</li>
<li>The exact shape: the numbers are a plan for discussion. Your surgeon decides the operation with you.</li></ul>)";

/// The scan's line for the record: file, points, noise, and the model against it.
std::string record_scan(const json& model)
{
  if (!model.contains("scan"))
    return "";
  const auto& sc = model.at("scan");
  const auto& d = sc.at("model_to_scan_mm");
  return fmt::format("<p>Landmarks measured on the scan {} ({} points, noise {:.2f} mm RMS{}). Model's standing skin to "
                     "the scan's: mean {:.1f} mm, 95 % within {:.1f} mm, largest {:.1f} mm (placed at the fold); "
                     "volume {:.0f} cm³ against the scan's {:.0f} cm³ ({:+.0f} %).</p>",
                     sc.at("file").get<std::string>(), sc.at("points").get<std::size_t>(),
                     sc.at("noise_rms_mm").get<double>(), sc.at("notch_given").get<bool>() ? ", notch on the scan" : "",
                     d.at("mean").get<double>(), d.at("p95").get<double>(), d.at("max").get<double>(),
                     sc.at("volume_cm3").at("model").get<double>(), sc.at("volume_cm3").at("scan").get<double>(),
                     100 * sc.at("volume_error").get<double>());
}

std::string record_breast(const std::string& side, const json& model, const json& plan)
{
  const auto& t = model.at("target");
  const auto& a = model.at("achieved");
  std::string rows;
  for (const char* k : {"sn_n_mm", "n_imf_mm", "base_width_mm", "nipple_midline_mm"})
    rows += fmt::format("<tr><td>{}</td><td>{:.1f}</td><td>{:.1f}</td></tr>", k, t.at(k).get<double>(), a.at(k).get<double>());
  const auto& p = plan.at("plan");
  std::string incision = "no operable plan";
  if (p.at("ok").get<bool>())
  {
    const auto& in = p.at("incision");
    incision = fmt::format("a = {:.1f} deg, s = {:.1f} mm, h = {:.1f} mm, d = {:.1f} mm; marking: new nipple SN-N "
                           "{:.1f} mm, vertical limb {:.1f} mm",
                           in.at("a_deg").get<double>(), 1e3 * in.at("s_m").get<double>(), 1e3 * in.at("h_m").get<double>(),
                           1e3 * in.at("d_m").get<double>(), p.at("surgical").at("new_nipple_sn_n_mm").get<double>(),
                           p.at("surgical").at("vertical_limb_mm").get<double>());
  }
  return fmt::format(
      "<h3>{0}</h3><table class=\"keep\"><tr><th>landmark [mm]</th><th>measured</th><th>model</th></tr>{1}</table>"
      "<p>Model: cap R = {2:.1f} mm, H = {3:.1f} mm, moduli x {4:.3g} (tissue mu = {5:.4g} Pa); largest landmark "
      "error {6:.2f} mm. Incision: {7}. Targets: {8}; {9}; {10} surgeries searched.</p>{11}",
      side, rows, 1e3 * model.at("R_m").get<double>(), 1e3 * model.at("H_m").get<double>(),
      model.at("stiffness_factor").get<double>(), model.at("tissue_mu_Pa").get<double>(),
      model.at("largest_error_mm").get<double>(), incision, targets_text(plan.at("targets")),
      plan.at("met").get<bool>() ? "all met" : "not met: " + plan.at("unmet").dump(), plan.at("searched").size(),
      record_scan(model));
}
/// The body's line for the record: height, weight, body surface area and
/// each breast's resection per m^2 of it, bra size (those given).
std::string record_body(const json& model, const json& plans)
{
  if (!model.contains("body"))
    return "";
  const auto& b = model.at("body");
  std::string s;
  auto add = [&](const std::string& part) { s += (s.empty() ? "" : ", ") + part; };
  if (b.contains("height_m"))
    add(fmt::format("height {:.0f} cm", 100 * b.at("height_m").get<double>()));
  if (b.contains("weight_kg"))
    add(fmt::format("weight {:.1f} kg", b.at("weight_kg").get<double>()));
  if (b.contains("bsa_m2"))
  {
    const double bsa = b.at("bsa_m2");
    add(fmt::format("body surface area {:.2f} m^2 (Mosteller)", bsa));
    for (const auto& p : plans)
      if (p.at("plan").at("ok").get<bool>())
        add(fmt::format("{} resection <span data-key=\"{}-g-per-m2\">{:.0f}</span> g/m^2",
                        p.at("side").get<std::string>(), p.at("side").get<std::string>(),
                        p.at("plan").at("surgical").at("resection_g").get<double>() / bsa));
  }
  if (b.contains("bra_size"))
    add("bra " + html_escape(b.at("bra_size").get<std::string>()));
  return "<p id=\"record-body\">Body: " + s + ".</p>";
}
} // namespace

std::string consult_report_html(const JobRecord& plan, const std::vector<ReportPicture>& pictures)
{
  const auto& models = plan.summary.at("patient_model").at("sides");
  const auto& plans = plan.summary.at("plan").at("sides");
  const std::string id = plan.summary.at("patient_model").value("id", "");
  const std::string date = plan.finished.substr(0, 10);
  std::string patient, record;
  for (const char* side : {"left", "right"})
    if (const json* p = side_of(plans, side))
    {
      patient += patient_breast(side, *side_of(models, side), *p);
      record += record_breast(side, *side_of(models, side), *p);
    }
  return fmt::format(
      "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Breast reduction plan {0}</title>"
      "<style>{1}</style></head><body><section id=\"for-patient\"><h1>Your breast reduction plan</h1>"
      "<p class=\"meta\">Patient <b data-key=\"patient-id\">{0}</b>, <span data-key=\"date\">{2}</span>. Measured "
      "standing; lengths along the skin.</p>{3}{4}{5}{6}</section>"
      "<section id=\"for-record\" class=\"page\"><h1>For the record</h1><p class=\"meta\">breastsim plan job {7}, "
      "solved {8}; the model's terms (docs/CLINIC.md).</p>{10}{9}</section></body></html>\n",
      html_escape(id.empty() ? "(no ID)" : id), report_style(), html_escape(date), pictures_section(pictures), patient,
      symmetry(models, plans), limits, plan.id, html_escape(plan.finished), record,
      record_body(plan.summary.at("patient_model"), plans));
}
} // namespace breastsim::app
