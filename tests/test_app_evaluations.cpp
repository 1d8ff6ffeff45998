// The calibration job's progress channel (src/app/job_evaluations.hpp): the
// library's evaluation message as an entry, the report's history as
// entries, the JSON lines after a cursor, the cursor's checks.
#include "errors.hpp"
#include "job_evaluations.hpp"
#include <filesystem>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace breastsim;
using nlohmann::json;

TEST(AppEvaluations, TheLibrarysMessageBecomesAnEntry)
{
  // The wording of calibrate.cpp: "eval {:>4}  chi2 = {:<12.6g} {}{}", the
  // parameters as "name = {:.5g} unit" joined by ", ".
  const std::string best = fmt::format("eval {:>4}  chi2 = {:<12.6g} {}{}", 3, 12.3456789,
                                       fmt::format("mu = {:.5g} Pa, c = {:.5g} Pa/m", 350.4321, 148012.7), "  *");
  const auto e = app::evaluation_from_message(best);
  ASSERT_TRUE(e);
  EXPECT_EQ((*e)["n"], 3);
  EXPECT_DOUBLE_EQ((*e)["chi2"].get<double>(), 12.3457);
  EXPECT_DOUBLE_EQ((*e)["params"]["mu"].get<double>(), 350.43);
  EXPECT_DOUBLE_EQ((*e)["params"]["c"].get<double>(), 1.4801e5);
  EXPECT_EQ((*e)["params"].size(), 2u);
  EXPECT_TRUE((*e)["best"].get<bool>());

  const auto plain = app::evaluation_from_message("eval 1234  chi2 = 0.000123456  R = 0.1 m, mu_s = 2.5e-07 Pa, "
                                                  "lambda = 1e+04 Pa");
  ASSERT_TRUE(plain);
  EXPECT_EQ((*plain)["n"], 1234);
  EXPECT_DOUBLE_EQ((*plain)["chi2"].get<double>(), 0.000123456);
  EXPECT_DOUBLE_EQ((*plain)["params"]["mu_s"].get<double>(), 2.5e-7);
  EXPECT_DOUBLE_EQ((*plain)["params"]["lambda"].get<double>(), 1e4);
  EXPECT_DOUBLE_EQ((*plain)["params"]["R"].get<double>(), 0.1);
  EXPECT_FALSE((*plain)["best"].get<bool>());

  // A misfit that is not finite: null (JSON has no inf).
  const auto inf = app::evaluation_from_message("eval    7  chi2 = inf          mu = 350 Pa");
  ASSERT_TRUE(inf);
  EXPECT_TRUE((*inf)["chi2"].is_null());

  for (const char* other : {"calibrating [mu,c] with bobyqa against 13 measurements in 3 postures",
                            "optimiser (bobyqa): converged after 12 evaluations", "eval", "eval    x  chi2 = 3",
                            "eval    3  chi2 = three  mu = 350 Pa", "eval    3  chi2 = 3  mu = 35o Pa",
                            "medieval    3  chi2 = 3  mu = 350 Pa", ""})
    EXPECT_FALSE(app::evaluation_from_message(other)) << other;
}

TEST(AppEvaluations, TheReportsHistory)
{
  const json history = json::parse(R"([
    {"evaluation": 1, "chi2": 40.25, "stage": "start", "parameters": {"mu": 500.0, "c": 100000.0}},
    {"evaluation": 2, "chi2": 3.0000000000000004, "stage": "fit", "parameters": {"mu": 350.4, "c": 148000.0}}])");
  const json e = app::evaluations_from_history(history);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0], json::parse(R"({"n": 1, "chi2": 40.25, "params": {"mu": 500.0, "c": 100000.0}, "stage": "start"})"));
  EXPECT_EQ(e[1]["chi2"].get<double>(), 3.0000000000000004); // exact
  EXPECT_EQ(e[1]["stage"], "fit");
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
