// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The scan upload: POST /api/scans?format=stl&units=mm&posture=standing
// [&mesh_size=0.01] [&use=model|consultation] with the file's bytes as the body (Content-Type:
// application/octet-stream, at most --max-upload bytes). The server names
// the file itself: it is written under <data>/uploads/<random>.<format>,
// read and checked as `scan-model` reads it (the scan readers and
// check_scan, with their messages; a refused file is removed), then moved
// into a new scan job's folder as scan.<format> and the job is queued
// (scan_job.hpp). No name or path from the request reaches the disk.
#include "job_queue.hpp"
#include "job_store.hpp"
#include <filesystem>
#include <httplib.h>
#include <map>
#include <string>

namespace breastsim::app
{
struct ScanUpload
{
  std::string format;   ///< stl, ply, obj
  std::string units;    ///< mm, m
  std::string posture;  ///< standing, supine, all_fours
  double mesh_size = 0; ///< 0 (by the breast's volume) or [0.001, 0.02] m
  std::string use;      ///< model (the scan job: model, neutral state, postures) or consultation (kept for a patient)
};

/// The query's fields checked with the CLI's messages; InputError naming
/// the field, the value and what is allowed.
ScanUpload checked_scan_upload(const std::multimap<std::string, std::string>& params);

/// Read and check the stored file as scan-model does (InputError with the
/// readers' and check_scan's message, the server's file name replaced by
/// "the uploaded scan").
void check_uploaded_scan(const std::filesystem::path& file, const ScanUpload& u);

/// POST /api/scans -> 202 {"id"} of the queued scan job; 400 with the
/// message, 415 for another content type. `data`: the claimed data folder
/// (its uploads/ emptied now).
void add_scan_routes(httplib::Server& server, JobStore& store, JobQueue& queue, const std::filesystem::path& data);
} // namespace breastsim::app
