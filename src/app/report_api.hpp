// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// POST /api/jobs/<id>/report: the printable report of a finished surgery
// (report.hpp) from the pictures the page rendered and the records of the
// job and of the calibration it names, written as report.html in the job's
// folder and added to the job's files (GET /api/jobs/<id>/files/report.html).
#include "job_store.hpp"
#include <httplib.h>

namespace breastsim::app
{
void add_report_routes(httplib::Server& server, JobStore& store);
} // namespace breastsim::app
