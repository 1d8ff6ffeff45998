// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The structured progress channel of a calibration job: every evaluation of
// the misfit as one JSON line {"n", "chi2", "params": {name: value},
// "stage", "best"} in DATA/jobs/<id>/evaluations.jsonl, appended by the job
// process as the library makes it (CalibrateOptions::on_evaluation: the
// history entry of report.json) and, when the calibration has ended,
// rewritten from report.json's history (the same entries). The API returns
// them with the job's record (GET /api/jobs/<id>?since=N: those after N).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::app
{
/// The file of a job folder.
inline const char* evaluations_file = "evaluations.jsonl";

/// The entries of a calibration report's "history" ({"evaluation", "chi2",
/// "stage", "parameters", "best"}): {"n", "chi2", "params", "stage", "best"};
/// a chi2 that is not finite becomes null.
nlohmann::json evaluations_from_history(const nlohmann::json& history);

/// The JSON objects of the complete lines of a JSON-lines text, in order: a
/// last line without its newline (still being written) and lines that are
/// not JSON objects are skipped.
nlohmann::json complete_json_lines(const std::string& jsonl);

/// The entries of an evaluations.jsonl text whose n exceeds `since`, in
/// order; lines that are not a complete entry (a line being written) are
/// skipped.
nlohmann::json evaluations_after(const std::string& jsonl, long since);

/// `since` of a request: "" -> 0, else an integer in [0, 10^9]; throws
/// InputError naming the value.
long parse_since(const std::string& text);

/// Append one entry to the job folder's evaluations.jsonl (flushed).
void append_evaluation(const std::filesystem::path& folder, const nlohmann::json& entry);
/// Replace the job folder's evaluations.jsonl by `entries` (atomically).
void write_evaluations(const std::filesystem::path& folder, const nlohmann::json& entries);
/// Every entry of the job folder's evaluations.jsonl after `since` ([] without the file).
nlohmann::json read_evaluations(const std::filesystem::path& folder, long since = 0);
} // namespace breastsim::app
