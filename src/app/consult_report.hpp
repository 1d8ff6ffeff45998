// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The consultation's report (docs/CLINIC.md, "The report"): from a finished
// plan job, one page for the patient in plain words - her ID, the date,
// each breast's tissue removed, nipple and fold before and after, the
// volumes and their symmetry, the pictures, and what the simulation cannot
// predict - and one for the surgeon's record with the model's terms (the
// landmarks' fit, R, H, moduli, the incision a, s, h, d, the targets and the
// search). One HTML file with print CSS: each part prints on its own pages.
#include "job_record.hpp"
#include "report.hpp"

namespace breastsim::app
{
std::string consult_report_html(const JobRecord& plan, const std::vector<ReportPicture>& pictures);
} // namespace breastsim::app
