// SPDX-License-Identifier: LGPL-3.0-or-later
// The structured progress of simulate, surgery and sweep jobs: Progress
// (the library's callback, parts mapped onto their share of the whole) and
// the job's progress channel (progress_channel.cpp: progress.jsonl written
// by the job process, its last complete entry read by the server).
#include "progress.hpp"
#include "progress_channel.hpp"
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>
#include <utility>
#include <vector>

using namespace breastsim;
namespace fs = std::filesystem;

TEST(AppProgress, PartsMapOntoTheirShareOfTheWhole)
{
  std::vector<std::pair<std::string, double>> seen;
  const Progress whole([&](const std::string& s, double f) { seen.emplace_back(s, f); });
  whole.report("meshing", 0);
  // a surgery of 2 postures inside the 3rd of 4 sweep cases: [0.5, 0.75]
  const Progress sweep_case = whole.part(0.5, 0.75, "a=30 (3 of 4): ");
  const Progress pre = sweep_case.part(1.0 / 7, 3.0 / 7, "pre-operative ");
  pre.report("posture supine (2 of 2)", 0.5);
  sweep_case.report("finished", 1);
  whole.report("beyond", 1.5); // clamped
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[0], std::make_pair(std::string("meshing"), 0.0));
  EXPECT_EQ(seen[1].first, "a=30 (3 of 4): pre-operative posture supine (2 of 2)");
  EXPECT_NEAR(seen[1].second, 0.5 + 0.25 * (1.0 / 7 + 0.5 * 2.0 / 7), 1e-15);
  EXPECT_NEAR(seen[2].second, 0.75, 1e-15);
  EXPECT_NEAR(seen[3].second, 1.0, 1e-15);
  Progress{}.part(0, 1).report("nowhere", 0.5); // an empty Progress reports nothing
}

TEST(AppProgress, ChannelKeepsCompleteEntriesInOrder)
{
  const std::string text = "{\"n\":1,\"stage\":\"meshing\",\"fraction\":0}\n"
                           "not json\n"
                           "{\"n\":2,\"stage\":7,\"fraction\":0.1}\n"
                           "{\"n\":3,\"stage\":\"posture standing (1 of 2)\",\"fraction\":0.25}\n"
                           "{\"n\":4,\"stage\":\"pos";
  const auto entries = app::progress_entries(text);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[1]["n"], 3);
  const auto p = app::last_progress(text);
  EXPECT_EQ(p.stage, "posture standing (1 of 2)");
  EXPECT_DOUBLE_EQ(p.fraction, 0.25);
  EXPECT_EQ(app::last_progress("").stage, "");
  EXPECT_DOUBLE_EQ(app::last_progress("{\"n\":9,\"stage\":\"finished\",\"fraction\":1}\n").fraction, 0.99);
}

TEST(AppProgress, JobProcessAppendsNumberedEntries)
{
  const fs::path dir = fs::temp_directory_path() / ("breastsim_progress_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Progress p = app::progress_into(dir);
  p.report("meshing", 0);
  p.part(0.25, 0.5, "pre-operative ").report("posture standing (1 of 1)", 0);
  std::ifstream f(dir / app::progress_file);
  std::stringstream s;
  s << f.rdbuf();
  const auto entries = app::progress_entries(s.str());
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0]["n"], 1);
  EXPECT_EQ(entries[1]["n"], 2);
  EXPECT_EQ(entries[1]["stage"], "pre-operative posture standing (1 of 1)");
  EXPECT_DOUBLE_EQ(entries[1]["fraction"].get<double>(), 0.25);
  fs::remove_all(dir);
}
