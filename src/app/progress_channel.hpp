// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The structured progress channel of a simulate, surgery, sweep or scan job:
// every stage the library reports (breastsim::Progress: the stage that
// begins and the fraction of the job done before it) as one JSON line
// {"n", "stage", "fraction"} of DATA/jobs/<id>/progress.jsonl, appended and
// flushed by the job process. The server reads the last complete line into
// the job's record (progress bar and stage), never the log's wording.
#include "job_progress.hpp"
#include "progress.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::app
{
inline const char* progress_file = "progress.jsonl";

/// A Progress whose reports are appended to `folder`'s progress.jsonl,
/// numbered from 1 (rank 0 of MPI_COMM_WORLD only).
Progress progress_into(const std::filesystem::path& folder);

/// The entries of a progress.jsonl text, in order; a line that is not a
/// complete entry (the last one, still being written) is skipped.
nlohmann::json progress_entries(const std::string& jsonl);

/// The last complete entry of `jsonl` as the job's progress (fraction at
/// most 0.99: the record reads 1 only when the job is done); {0, ""}
/// without one.
JobProgress last_progress(const std::string& jsonl);
} // namespace breastsim::app
