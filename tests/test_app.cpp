// SPDX-License-Identifier: LGPL-3.0-or-later
// The planning app's pieces that need no server: job ids, the case from
// JSON overrides, a calibration's progress, the lower-pole volumes of a
// skin surface, the serve options and the data folder rules.
#include "case_request.hpp"
#include "data_folder.hpp"
#include "errors.hpp"
#include "input_error_message.hpp"
#include "job_id.hpp"
#include "job_progress.hpp"
#include "result_summary.hpp"
#include "serve_options.hpp"
#include <cmath>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace breastsim;
namespace fs = std::filesystem;

namespace
{
using fixtures::message_of;

/// The outer skin of a quarter sphere of radius r (x >= 0, y >= 0), centred
/// at the origin, as a surface document: counter-clockwise from outside.
nlohmann::json quarter_sphere(double r, int n)
{
  std::vector<double> x;
  std::vector<std::int64_t> t;
  // polar angle from +y (0..pi/2), azimuth in the x-z plane from -z to +z over x >= 0
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= 2 * n; ++j)
    {
      const double a = M_PI / 2 * i / n, b = -M_PI / 2 + M_PI * j / (2 * n);
      x.insert(x.end(), {r * std::sin(a) * std::cos(b), r * std::cos(a), r * std::sin(a) * std::sin(b)});
    }
  auto id = [n](int i, int j) { return static_cast<std::int64_t>(i * (2 * n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j)
      for (auto [p, q, s] : {std::array{id(i, j), id(i + 1, j), id(i + 1, j + 1)},
                             std::array{id(i, j), id(i + 1, j + 1), id(i, j + 1)}})
      {
        // orient outward: (q - p) x (s - p) along the position
        const double* P = &x[3 * p]; const double* Q = &x[3 * q]; const double* S = &x[3 * s];
        const double u[3] = {Q[0] - P[0], Q[1] - P[1], Q[2] - P[2]}, v[3] = {S[0] - P[0], S[1] - P[1], S[2] - P[2]};
        const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        const bool out = c[0] * (P[0] + Q[0] + S[0]) + c[1] * (P[1] + Q[1] + S[1]) + c[2] * (P[2] + Q[2] + S[2]) > 0;
        t.insert(t.end(), {p, out ? q : s, out ? s : q});
      }
  return {{"vertices", x}, {"triangles", t}};
}
} // namespace

TEST(AppJobId, GeneratedIdsPassTheCheckOthersDoNot)
{
  const auto id = app::new_job_id();
  EXPECT_TRUE(app::is_job_id(id));
  EXPECT_NE(id, app::new_job_id());
  for (const char* bad : {"", "..", "0123456789abcde", "0123456789abcdef0", "0123456789ABCDEF",
                          "../../etc/passwd", "0123456789abcde/"})
    EXPECT_FALSE(app::is_job_id(bad)) << bad;
}

TEST(AppCaseRequest, JsonValuesGoThroughTheCliParseAndMessages)
{
  const auto c = app::case_from_overrides(
      {{"incision.a_deg", 35}, {"postures.names", {"standing", "supine"}}, {"base.fixed", true}});
  EXPECT_EQ(c.number("incision.a_deg"), 35);
  EXPECT_EQ(c.strings("postures.names").size(), 2u);
  EXPECT_TRUE(c.flag("base.fixed"));
  EXPECT_EQ(app::posture_count(c), 2u);
  EXPECT_EQ(message_of([] { app::case_from_overrides({{"incision.a_deg", 95}}); }),
            "key 'incision.a_deg' = 95 is out of range: allowed (0, 90) deg");
  EXPECT_NE(message_of([] { app::case_from_overrides({{"tissue.mu", {{"x", 1}}}}); }).find("tissue.mu"),
            std::string::npos);
  EXPECT_NE(message_of([] { app::case_from_overrides({{"solver.petsc_options", "-log_view :/x"}}); })
                .find("not accepted by breastsim serve"),
            std::string::npos);
  EXPECT_NE(message_of([] { app::case_from_overrides(nlohmann::json::array()); }).find("JSON object"),
            std::string::npos);
}

TEST(AppProgress, CalibrationCountsItsEvaluations)
{
  // A calibration: its evaluations (the structured channel) over max_evals, at most 0.95.
  const auto cal = app::calibration_progress(10, 2, "[1] calibrating [mu,c]\n[2] eval    2  chi2 = 2\n");
  EXPECT_NEAR(cal.fraction, 0.2, 1e-12);
  EXPECT_EQ(cal.stage, "eval    2  chi2 = 2");
  EXPECT_NEAR(app::calibration_progress(10, 14, "").fraction, 0.95, 1e-12);
  EXPECT_NEAR(app::calibration_progress(0, 0, "").fraction, 0, 1e-12);
}

TEST(AppPoleVolumes, QuarterSphereHalfBelowTheEquator)
{
  const double r = 0.05;
  const auto v = breastsim::pole_volumes(quarter_sphere(r, 40), 0.0);
  const double exact = M_PI * r * r * r / 3; // a quarter of the ball
  EXPECT_NEAR(v.total / exact, 1, 2e-3);
  EXPECT_NEAR(v.lower / v.total, 0.5, 1e-9);
  EXPECT_NEAR(breastsim::pole_volumes(quarter_sphere(r, 40), -r).lower, 0, 1e-12);
}

TEST(AppServeOptions, RangesAndLoopback)
{
  app::ServeOptions o;
  EXPECT_EQ(message_of([&] { app::check_serve_options(o); }), "");
  o.workers = 17;
  EXPECT_EQ(message_of([&] { app::check_serve_options(o); }), "--workers = 17 is out of range: allowed [1, 16]");
  o = {};
  o.host = "0.0.0.0";
  EXPECT_NE(message_of([&] { app::check_serve_options(o); }).find("given explicitly"), std::string::npos);
  o.host_given = true;
  EXPECT_EQ(message_of([&] { app::check_serve_options(o); }), "");
  EXPECT_TRUE(app::is_loopback("127.0.0.1") && app::is_loopback("localhost") && !app::is_loopback("10.0.0.1"));
}

TEST(AppDataFolder, OnlyNewEmptyOrItsOwnFolders)
{
  const fs::path scratch = fs::temp_directory_path() / ("breastsim_app_" + std::to_string(getpid()));
  fs::create_directories(scratch / "notes");
  std::ofstream(scratch / "notes" / "keep.txt") << "mine";
  EXPECT_NE(message_of([&] { app::claim_data_folder((scratch / "notes").string()); }).find("not empty"),
            std::string::npos);
  EXPECT_EQ(fs::directory_iterator(scratch / "notes")->path().filename(), "keep.txt");
  const auto data = app::claim_data_folder((scratch / "data").string());
  EXPECT_TRUE(fs::exists(data / "jobs") && fs::exists(data / app::data_marker));
  std::ofstream(data / "jobs" / "x") << "";
  EXPECT_EQ(app::claim_data_folder((scratch / "data").string()), data); // its own folder again
  EXPECT_NE(message_of([] { app::claim_data_folder("/"); }).find("file-system root"), std::string::npos);
  fs::remove_all(scratch);
}
