// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The printable report of a finished surgery: pictures from the page's
// renderer (PNG) and the numbers of the job's record: the plan (a, s, h, d)
// and breast model, the resected volume and weight, per posture the nipple
// before and after with its distance to the base and the lower-pole share
// against the ideals, and the fitted parameters with their 95 % intervals of
// the calibration the plan used. One HTML file with the pictures inline and
// print CSS (A4, no page break inside a table or picture): the browser's
// "Save as PDF" or `chromium --headless --print-to-pdf` gives the PDF.
#include "job_record.hpp"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim::app
{
struct ReportPicture
{
  std::string caption;
  std::string png_base64; ///< checked: base64 of a PNG file
};

/// The pictures of a report request {"pictures": [{"caption", "png"}, ...],
/// "calibration": id or null}: at most 8, captions of at most 200
/// characters, each "png" the base64 of a PNG file of at most 4 MB.
/// InputError naming the field otherwise.
std::vector<ReportPicture> report_pictures(const nlohmann::json& request);
/// The report of the finished surgery `surgery`; `calibration` (a finished
/// calibration) or nullptr.
std::string report_html(const JobRecord& surgery, const JobRecord* calibration,
                        const std::vector<ReportPicture>& pictures);
/// The reports' CSS (screen and A4 print; class "page" starts a new page).
const char* report_style();
/// The pictures as figures with their captions ("" without pictures).
std::string pictures_section(const std::vector<ReportPicture>& pictures);
/// `text` with &, <, >, " and ' escaped for HTML.
std::string html_escape(const std::string& text);
/// The bytes of base64 `text` (RFC 4648 alphabet, padding optional but,
/// when present, completing the last group of 4); InputError if it is not
/// base64.
std::string base64_decode(const std::string& text);
} // namespace breastsim::app
