// SPDX-License-Identifier: LGPL-3.0-or-later
// The Patient step's files at the server's edge: the scan upload's fields
// (scan_upload.cpp) with the CLI's messages, the stored file's check naming
// "the uploaded scan" (never the server's path), and the recording check
// (recording_api.cpp) with its bound on the points.
#include "case_request.hpp"
#include "errors.hpp"
#include "input_error_message.hpp"
#include "recording_api.hpp"
#include "scan_upload.hpp"
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace breastsim;
using fixtures::message_of;
using Params = std::multimap<std::string, std::string>;

TEST(AppUploads, ScanFieldsCheckedWithTheCliMessages)
{
  const auto u = app::checked_scan_upload({{"format", "ply"}, {"units", "m"}});
  EXPECT_EQ(u.format, "ply");
  EXPECT_EQ(u.units, "m");
  EXPECT_EQ(u.posture, "standing");
  EXPECT_EQ(u.mesh_size, 0);
  for (const char* ok : {"0", "0.001", "0.02", "0.0125"})
    EXPECT_EQ(message_of([&] { app::checked_scan_upload({{"format", "stl"}, {"units", "mm"}, {"mesh_size", ok}}); }), "")
        << ok;
  const std::vector<std::pair<Params, std::string>> refused = {
      {{{"format", "stl"}, {"units", "cm"}}, "units = 'cm': the unit of the scan's coordinates must be stated: mm or m"},
      {{{"format", "stl"}}, "units: the unit of the scan's coordinates must be stated: mm or m"},
      {{{"units", "mm"}}, "format = '': allowed obj, ply, stl"},
      {{{"format", "STL/../x"}, {"units", "mm"}}, "format = 'STL/../x': allowed obj, ply, stl"},
      {{{"format", "stl"}, {"units", "mm"}, {"posture", "prone"}}, "posture = 'prone': allowed all_fours, standing, supine"},
      {{{"format", "stl"}, {"units", "mm"}, {"mesh_size", "0.0009"}}, "mesh_size = 0.0009 is out of range"},
      {{{"format", "stl"}, {"units", "mm"}, {"mesh_size", "0.021"}}, "mesh_size = 0.021 is out of range"},
      {{{"format", "stl"}, {"units", "mm"}, {"mesh_size", "0.01 "}}, "mesh_size = 0.01  is out of range"},
      {{{"format", "stl"}, {"units", "mm"}, {"mesh_size", "nan"}}, "mesh_size = nan is out of range"},
      {{{"format", "stl"}, {"units", "mm"}, {"units", "mm"}}, "units: the unit of the scan's coordinates must be stated"},
      {{{"format", "stl"}, {"units", "mm"}, {"path", "/etc/passwd"}}, "field 'path' is not allowed in a scan upload"},
  };
  for (const auto& [params, text] : refused)
    EXPECT_NE(message_of([&] { app::checked_scan_upload(params); }).find(text), std::string::npos)
        << text << " | " << message_of([&] { app::checked_scan_upload(params); });
}

TEST(AppUploads, StoredScanRefusedWithoutTheServersPath)
{
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("breastsim_upload_" + std::to_string(getpid()) + ".stl");
  std::ofstream(file, std::ios::binary) << "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n";
  const std::string m = message_of([&] { app::check_uploaded_scan(file, {"stl", "mm", "standing", 0}); });
  std::filesystem::remove(file);
  EXPECT_NE(m.find("the uploaded scan"), std::string::npos) << m;
  EXPECT_NE(m.find("a vertex needs three numbers"), std::string::npos) << m;
  EXPECT_EQ(m.find(file.filename().string()), std::string::npos) << m;
  EXPECT_EQ(m.find(std::filesystem::temp_directory_path().string()), std::string::npos) << m;
}

namespace
{
nlohmann::json recording(std::size_t points_per_posture)
{
  nlohmann::json postures = nlohmann::json::array();
  for (const auto& [name, theta] : {std::pair<const char*, double>{"standing", 0.0}, {"supine", 90.0}})
  {
    nlohmann::json pts = nlohmann::json::array();
    for (std::size_t k = 0; k < points_per_posture; ++k)
      pts.push_back({0.001 * static_cast<double>(k % 50), 0.03, -0.001 * static_cast<double>(k % 40)});
    postures.push_back({{"name", name}, {"theta_deg", theta}, {"points", pts}});
  }
  return {{"format", "breastsim-recording/1"}, {"units", "m"}, {"noise_sigma", 0.0005}, {"postures", postures}};
}
} // namespace

TEST(AppUploads, RecordingCheckedAsCalibrateReadsIt)
{
  const auto ok = app::check_recording(recording(12));
  EXPECT_EQ(ok["points"], 24);
  EXPECT_EQ(ok["postures"][1]["name"], "supine");
  EXPECT_EQ(ok["postures"][1]["points"], 12);
  EXPECT_EQ(ok["postures"][0]["nipple"], false);
  EXPECT_DOUBLE_EQ(ok["noise_sigma_m"].get<double>(), 0.0005);
  EXPECT_EQ(message_of([] { app::check_recording(recording(10000)); }), ""); // 20000 in all: the bound
  EXPECT_NE(message_of([] { app::check_recording(recording(10001)); })
                .find("20002 skin points in all is out of range: allowed [10, 20000]"),
            std::string::npos);
  auto bad = recording(12);
  bad["postures"][0]["points"][3][1] = 30.0; // millimetres written as metres
  const auto answer = app::recording_check_answer(bad);
  EXPECT_EQ(answer["ok"], false);
  EXPECT_NE(answer["error"].get<std::string>().find("key 'postures[0].points[3][1]'"), std::string::npos) << answer;
  EXPECT_NE(app::recording_check_answer({{"format", "other"}})["error"].get<std::string>().find("format"),
            std::string::npos);
  EXPECT_EQ(app::recording_check_answer(recording(12))["ok"], true);
}

TEST(AppUploads, NoFilePathFromARequest)
{
  for (const char* path : {"/etc/passwd", "../../jobs/x/scan.msh", "reference.msh"})
    EXPECT_NE(message_of([&] { app::case_from_overrides({{"geometry.mesh_file", path}}); })
                  .find("key 'geometry.mesh_file' = \"" + std::string(path) +
                        "\" is not accepted by breastsim serve (no file path from a request"),
              std::string::npos)
        << path;
  EXPECT_EQ(message_of([] { app::case_from_overrides({{"geometry.mesh_file", ""}}); }), "");
}
