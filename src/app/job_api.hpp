// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The job routes of the API: POST /api/jobs {kind, overrides} -> id,
// GET /api/jobs, GET /api/jobs/<id>, POST /api/jobs/<id>/cancel,
// GET /api/jobs/<id>/files/<name>, GET /api/jobs/<id>/result.tar (the
// result folder of a finished job as one archive). Ids match 16 hex digits
// in the route itself; a file is served only if its name is one the job's
// record lists (files the job wrote), and only from inside the job's folder.
#include "job_queue.hpp"
#include <httplib.h>

namespace breastsim::app
{
void add_job_routes(httplib::Server& server, JobStore& store, JobQueue& queue);
/// A record as the API shows it (no file-system paths).
nlohmann::json public_record(const JobRecord& r);
} // namespace breastsim::app
