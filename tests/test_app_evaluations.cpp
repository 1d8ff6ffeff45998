// SPDX-License-Identifier: LGPL-3.0-or-later
// The calibration job's progress channel (src/app/job_evaluations.hpp): the
// report's history entries (also what the library streams) as entries, the JSON lines after a cursor, the cursor's checks.
#include "errors.hpp"
#include "job_evaluations.hpp"
#include <filesystem>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace breastsim;
using nlohmann::json;

TEST(AppEvaluations, TheReportsHistory)
{
  const json history = json::parse(R"([
    {"evaluation": 1, "chi2": 40.25, "stage": "start", "parameters": {"mu": 500.0, "c": 100000.0}},
    {"evaluation": 2, "chi2": 3.0000000000000004, "stage": "fit", "parameters": {"mu": 350.4, "c": 148000.0},
     "best": true},
    {"evaluation": 3, "chi2": null, "stage": "fit", "parameters": {"mu": 1e9, "c": 148000.0}, "best": false}])");
  const json e = app::evaluations_from_history(history);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0], json::parse(R"({"n": 1, "chi2": 40.25, "params": {"mu": 500.0, "c": 100000.0}, "stage": "start",
                                  "best": false})"));
  EXPECT_EQ(e[1]["chi2"].get<double>(), 3.0000000000000004); // exact
  EXPECT_EQ(e[1]["stage"], "fit");
  EXPECT_TRUE(e[1]["best"].get<bool>());
  EXPECT_TRUE(e[2]["chi2"].is_null()); // a failed solve's misfit (inf in the library)
  EXPECT_EQ(app::evaluations_from_history(json::array()), json::array());
}

TEST(AppEvaluations, EntriesAfterACursor)
{
  const std::string text = "{\"n\":1,\"chi2\":4.5,\"params\":{}}\n"
                           "not json\n"
                           "{\"n\":2,\"chi2\":3.5,\"params\":{}}\n"
                           "{\"chi2\":1}\n"
                           "{\"n\":\"3\",\"chi2\":1}\n"
                           "{\"n\":3,\"chi2\":2.5,\"params\":{}}\n";
  EXPECT_EQ(app::evaluations_after(text, 0).size(), 3u);
  const json after = app::evaluations_after(text, 1);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0]["n"], 2);
  EXPECT_EQ(after[1]["chi2"], 2.5);
  EXPECT_EQ(app::evaluations_after(text, 3), json::array());
  // A last line without its newline is being written: not yet an entry.
  EXPECT_EQ(app::evaluations_after(text + "{\"n\":4,\"chi2\":1.5", 0).size(), 3u);
  EXPECT_EQ(app::evaluations_after(text + "{\"n\":4,\"chi2\":1.5}", 0).size(), 3u);
  EXPECT_EQ(app::evaluations_after("", 0), json::array());
}

TEST(AppEvaluations, TheCursorsRange)
{
  EXPECT_EQ(app::parse_since(""), 0);
  EXPECT_EQ(app::parse_since("0"), 0);
  EXPECT_EQ(app::parse_since("17"), 17);
  EXPECT_EQ(app::parse_since("1000000000"), 1000000000);
  for (const char* bad : {"-1", "1000000001", "abc", "1.5", "12x", " 1", "+1", "99999999999999999999999"})
  {
    try
    {
      app::parse_since(bad);
      ADD_FAILURE() << bad;
    }
    catch (const InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find("allowed an integer in [0, 1000000000]"), std::string::npos) << bad;
    }
  }
}

TEST(AppEvaluations, TheJobFoldersFile)
{
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("breastsim-evals-{}", getpid());
  std::filesystem::create_directories(dir);
  EXPECT_EQ(app::read_evaluations(dir), json::array()); // no file yet
  app::append_evaluation(dir, {{"n", 1}, {"chi2", 2.0}, {"params", {{"mu", 350.0}}}, {"best", true}});
  app::append_evaluation(dir, {{"n", 2}, {"chi2", 1.0}, {"params", {{"mu", 360.0}}}, {"best", true}});
  EXPECT_EQ(app::read_evaluations(dir).size(), 2u);
  EXPECT_EQ(app::read_evaluations(dir, 1)[0]["params"]["mu"], 360.0);
  const json exact = {{{"n", 1}, {"chi2", 0.1 + 0.2}, {"params", json::object()}, {"stage", "start"}}};
  app::write_evaluations(dir, exact);
  EXPECT_EQ(app::read_evaluations(dir), exact);
  EXPECT_EQ(app::read_evaluations(dir)[0]["chi2"].get<double>(), 0.1 + 0.2);
  EXPECT_FALSE(std::filesystem::exists(dir / "evaluations.jsonl.tmp"));
  std::filesystem::remove_all(dir);
}
