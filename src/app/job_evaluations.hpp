#pragma once
// The structured progress channel of a calibration job: every evaluation of
// the misfit as one JSON line {"n", "chi2", "params": {name: value}, "best"}
// in DATA/jobs/<id>/evaluations.jsonl, appended by the job process while it
// runs and, when the calibration has ended, rewritten from report.json's
// history (exact values, with each evaluation's "stage"). The API returns
// them with the job's record (GET /api/jobs/<id>?since=N: those after N).
//
// calibrate() reports an evaluation only through its progress line (its
// Objective's callback is internal to it), so while the job runs the entries
// are read from that one message of the library, in the job process, as it
// is logged (chi2 to the 6 significant digits, the parameters to the 5 of
// the line); the report's history then replaces them.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace breastsim::app
{
/// The file of a job folder.
inline const char* evaluations_file = "evaluations.jsonl";

/// One evaluation from the library's progress message
/// "eval    3  chi2 = 12.3456      mu = 350.4 Pa, c = 1.48e+05 Pa/m  *"
/// (the '*' marks the best point so far): {"n", "chi2", "params", "best"};
/// nullopt for any other message. A chi2 that is not finite becomes null.
std::optional<nlohmann::json> evaluation_from_message(const std::string& message);

/// The entries of a calibration report's "history" ({"evaluation", "chi2",
/// "stage", "parameters"}): {"n", "chi2", "params", "stage"}.
nlohmann::json evaluations_from_history(const nlohmann::json& history);

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
