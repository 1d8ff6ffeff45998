// SPDX-License-Identifier: LGPL-3.0-or-later
#include "report.hpp"
#include "case_request.hpp"
#include "errors.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::app
{
namespace
{
constexpr std::size_t max_pictures = 8, max_caption = 200, max_png = 4u << 20;

const char* const style_text = R"(
body { font: 11pt/1.35 system-ui, sans-serif; color: #222; margin: 2em auto; max-width: 60em; }
h1 { font-size: 1.5em; margin-bottom: 0.1em; } h2 { font-size: 1.15em; margin: 1.2em 0 0.3em; }
.meta { color: #555; } .hint { color: #555; font-size: 0.9em; }
table { border-collapse: collapse; margin: 0.3em 0; }
td, th { border: 1px solid #bbb; padding: 0.15em 0.5em; text-align: right; }
th { background: #eee; } td:first-child, th:first-child { text-align: left; }
.ok { color: #1e7d3a; } .off { color: #b9770e; }
.pictures { display: flex; flex-wrap: wrap; gap: 1em; }
.page { break-before: page; }
figure { margin: 0; width: 48%; } figure img { width: 100%; border: 1px solid #ccc; }
figcaption { font-size: 0.9em; color: #444; }
@page { size: A4; margin: 15mm; }
@media print {
  body { margin: 0; max-width: none; font-size: 10pt; }
  table, figure, .keep { break-inside: avoid; }
  h2 { break-after: avoid; }
  a { color: inherit; text-decoration: none; }
}
)";

std::string f1(double x)
{
  return fmt::format("{:.1f}", x);
}

std::string g4(double x)
{
  return fmt::format("{:.4g}", x);
}

std::string plan_table(const Config& c)
{
  return fmt::format(
      "<table class=\"keep\"><tr><th>incision</th><th>value</th></tr>"
      "<tr><td>a: angle of P1 with the symmetry plane</td><td>{} deg</td></tr>"
      "<tr><td>s: height of the new nipple A above the base centre</td><td>{} mm</td></tr>"
      "<tr><td>h: height of D above the base</td><td>{} mm</td></tr>"
      "<tr><td>d: depth of C (the new inframammary fold)</td><td>{} mm</td></tr></table>"
      "<table class=\"keep\"><tr><th>breast model</th><th>value</th></tr>"
      "<tr><td>base radius R, height H</td><td>{}, {} mm</td></tr>"
      "<tr><td>mesh size</td><td>{} mm</td></tr>"
      "<tr><td>tissue shear modulus, density</td><td>{} Pa, {} kg/m³</td></tr>"
      "<tr><td>skin shear modulus</td><td>{} Pa</td></tr></table>",
      f1(c.number("incision.a_deg")), f1(1e3 * c.number("incision.s")), f1(1e3 * c.number("incision.h")),
      f1(1e3 * c.number("incision.d")), f1(1e3 * c.number("geometry.R")), f1(1e3 * c.number("geometry.H")),
      f1(1e3 * c.number("geometry.mesh_size")), g4(c.number("tissue.mu")), g4(c.number("tissue.rho")),
      g4(c.number("skin.mu")));
}

std::string ideal_class(double value, double ideal, double tolerance)
{
  return std::abs(value - ideal) <= tolerance ? "ok" : "off";
}

std::string postures_table(const nlohmann::json& s)
{
  const double ideal_nb = s.at("ideal").at("nipple_to_base_mm"), ideal_lp = s.at("ideal").at("lower_pole_share");
  std::string html = "<table class=\"keep\"><tr><th>posture</th><th>nipple y, z before [mm]</th>"
                     "<th>nipple y, z after [mm]</th><th>nipple to base before [mm]</th>"
                     "<th>nipple to base after [mm]</th><th>lower pole before</th><th>lower pole after</th></tr>";
  const auto share = [](const nlohmann::json& v) {
    return v.contains("lower_pole_share") ? fmt::format("{:.0f} %", 100 * v.at("lower_pole_share").get<double>())
                                          : std::string("–");
  };
  for (const auto& p : s.at("postures"))
  {
    const auto &a = p.at("pre"), &b = p.at("post");
    const double nb = b.at("nipple_to_base_mm");
    html += fmt::format(
        "<tr data-posture=\"{}\"><td>{}</td><td>{}, {}</td><td>{}, {}</td><td>{}</td>"
        "<td class=\"{}\" data-key=\"post_nipple_to_base_mm\">{}</td><td>{}</td><td class=\"{}\">{}</td></tr>",
        html_escape(p.at("posture").get<std::string>()), html_escape(p.at("posture").get<std::string>()), f1(a.at("nipple_mm")[1]),
        f1(a.at("nipple_mm")[2]), f1(b.at("nipple_mm")[1]), f1(b.at("nipple_mm")[2]),
        f1(a.at("nipple_to_base_mm")), ideal_class(nb, ideal_nb, 5), f1(nb), share(a),
        ideal_class(b.value("lower_pole_share", 0.0), ideal_lp, 0.05), share(b));
  }
  return html + fmt::format("</table><p class=\"hint\">Ideals: nipple to base ≈ {:.0f} mm (standing); lower "
                            "pole ≈ {:.0f} % of the volume in front of the chest wall (below the nipple).</p>",
                            ideal_nb, 100 * ideal_lp);
}

std::string calibration_section(const JobRecord* cal)
{
  if (!cal)
    return "<h2>Fitted parameters</h2><p>No calibration: the breast model's values as entered.</p>";
  const auto& s = cal->summary;
  std::string html = fmt::format(
      "<h2>Fitted parameters</h2><p>Calibration {} ({} measurements, {} evaluations): misfit χ² {} → "
      "{}.</p><table class=\"keep\"><tr><th>parameter</th><th>start</th><th>fitted</th>"
      "<th>95 % interval</th><th>identifiability</th></tr>",
      cal->id, s.value("measurements", 0), s.value("evaluations", 0), g4(s.at("chi2_before")),
      g4(s.at("chi2_after")));
  for (const auto& p : s.at("parameters"))
    html += fmt::format("<tr><td>{} [{}]</td><td>{}</td><td data-key=\"fitted-{}\">{}</td><td>{} – {}</td>"
                        "<td style=\"text-align:left\">{}</td></tr>",
                        html_escape(p.at("name").get<std::string>()), html_escape(p.at("unit").get<std::string>()), g4(p.at("initial")),
                        html_escape(p.at("name").get<std::string>()), g4(p.at("fitted")), g4(p.at("interval_95")[0]),
                        g4(p.at("interval_95")[1]), html_escape(p.at("identifiability").get<std::string>()));
  return html + "</table>";
}

} // namespace

const char* report_style()
{
  return style_text;
}

std::string pictures_section(const std::vector<ReportPicture>& pictures)
{
  if (pictures.empty())
    return "";
  std::string html = "<h2>Pictures</h2><div class=\"pictures\">";
  for (const auto& p : pictures)
    html += fmt::format("<figure><img alt=\"{0}\" src=\"data:image/png;base64,{1}\"><figcaption>{0}"
                        "</figcaption></figure>",
                        html_escape(p.caption), p.png_base64);
  return html + "</div>";
}

std::string html_escape(const std::string& text)
{
  std::string out;
  out.reserve(text.size());
  for (char ch : text)
    switch (ch)
    {
    case '&': out += "&amp;"; break;
    case '<': out += "&lt;"; break;
    case '>': out += "&gt;"; break;
    case '"': out += "&quot;"; break;
    case '\'': out += "&#39;"; break;
    default: out += ch;
    }
  return out;
}

std::string base64_decode(const std::string& text)
{
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string n = text;
  while (!n.empty() && n.back() == '=' && text.size() - n.size() < 2)
    n.pop_back();
  if (n.size() % 4 == 1)
    throw InputError("not base64: its length is impossible");
  if (n.size() != text.size() && text.size() % 4 != 0) // padding completes the last group of 4
    throw InputError("not base64: '=' padding that does not complete a group of 4 characters");
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (char ch : n)
  {
    const auto v = alphabet.find(ch);
    if (v == std::string::npos)
      throw InputError("not base64: a character outside A-Z, a-z, 0-9, +, /");
    bits = (bits << 6) | static_cast<unsigned>(v); // 4 characters of 6 bits -> 3 bytes
    if ((count += 6) >= 8)
    {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xff);
    }
  }
  return out;
}

std::vector<ReportPicture> report_pictures(const nlohmann::json& request)
{
  if (!request.is_object())
    throw InputError("the report request must be an object {\"pictures\": [...], \"calibration\": id or null}");
  for (const auto& [key, v] : request.items())
    if (key != "pictures" && key != "calibration")
      throw InputError("unknown field '" + key + "' in the report request: allowed pictures, calibration");
  const auto pics = request.value("pictures", nlohmann::json::array());
  if (!pics.is_array() || pics.size() > max_pictures)
    throw InputError(fmt::format("pictures: an array of at most {} pictures", max_pictures));
  std::vector<ReportPicture> out;
  for (std::size_t i = 0; i < pics.size(); ++i)
  {
    const auto& p = pics[i];
    const std::string field = fmt::format("pictures[{}]", i);
    if (!p.is_object() || p.size() != 2 || !p.contains("caption") || !p.contains("png") ||
        !p["caption"].is_string() || !p["png"].is_string())
      throw InputError(field + ": an object {\"caption\": text, \"png\": base64}");
    const std::string caption = p["caption"], png = p["png"];
    if (caption.size() > max_caption)
      throw InputError(fmt::format("{}.caption: {} characters, allowed at most {}", field, caption.size(), max_caption));
    if (png.size() > max_png / 3 * 4 + 4)
      throw InputError(fmt::format("{}.png: larger than {} MB", field, max_png >> 20));
    std::string bytes;
    try
    {
      bytes = base64_decode(png);
    }
    catch (const InputError& e)
    {
      throw InputError(field + ".png: " + e.what());
    }
    if (bytes.rfind("\x89PNG\r\n\x1a\n", 0) != 0)
      throw InputError(field + ".png: not a PNG file");
    out.push_back({caption, png});
  }
  return out;
}

std::string report_html(const JobRecord& surgery, const JobRecord* calibration,
                        const std::vector<ReportPicture>& pictures)
{
  const Config c = case_from_overrides(surgery.overrides);
  const auto& s = surgery.summary;
  return fmt::format(
      "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>breastsim report {0}</title>"
      "<style>{1}</style></head><body><h1>Breast reduction plan</h1><p class=\"meta\">breastsim surgery job {0}, "
      "solved {2}. A simulation of the paper's model, for planning: not a prediction for the patient.</p>"
      "<h2>Plan</h2>{3}<h2>Result</h2><p class=\"keep\">Resected volume <b data-key=\"resected_volume_cm3\">{4}"
      "</b> cm³, weight <b data-key=\"resected_weight_g\">{5}</b> g (ρ = {6} kg/m³); volume before {7} cm³, "
      "after {8} cm³; largest suture gap {9:.3f} mm.</p>{10}{11}{12}</body></html>\n",
      surgery.id, style_text, html_escape(surgery.finished), plan_table(c), f1(s.at("resected_volume_cm3")),
      f1(s.at("resected_weight_g")), g4(s.at("tissue_rho_kg_m3")), f1(s.at("volume_pre_cm3")),
      f1(s.at("volume_post_cm3")), s.at("max_suture_gap_mm").get<double>(), postures_table(s),
      calibration_section(calibration), pictures_section(pictures));
}
} // namespace breastsim::app
