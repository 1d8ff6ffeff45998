// SPDX-License-Identifier: LGPL-3.0-or-later
// The refusal rule of result folders (src/io/output_target.hpp) on a fake file
// system: a scratch folder stands in for "/", $HOME and the working
// directory, so the rule for the real root is tested without touching it.
#include "config.hpp"
#include "errors.hpp"
#include "output.hpp"
#include "output_target.hpp"
#include "sweep.hpp"
#include <fstream>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace breastsim;
namespace fs = std::filesystem;

namespace
{
struct FakeRoot : ::testing::Test
{
  fs::path root;
  OutputRules rules;

  void SetUp() override
  {
    root = fs::weakly_canonical(fs::temp_directory_path()
                                / ("breastsim_fake_root_" + std::to_string(getpid())));
    fs::remove_all(root);
    fs::create_directories(root / "home/user/work");
    rules.protect = {root, root / "home/user", root / "home/user/work"};
  }
  void TearDown() override { fs::remove_all(root); }

  void touch(const fs::path& p, const std::string& text = "x")
  {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
  }
  bool refused(const fs::path& p) { return refusal_reason(p, rules).has_value(); }
  std::string reason(const fs::path& p) { return refusal_reason(p, rules).value_or(""); }
};
} // namespace

TEST_F(FakeRoot, RootHomeAndWorkingDirectoryAreRefusedEvenWithAMarker)
{
  for (const fs::path& p : {root, root / "home", root / "home/user", root / "home/user/work"})
  {
    touch(p / result_marker, R"({"format": "breastsim result folder", "state": "complete"})");
    EXPECT_TRUE(refused(p)) << p;
    EXPECT_NE(reason(p).find(p.string()), std::string::npos) << reason(p);
  }
  EXPECT_NE(reason(root).find("file-system root"), std::string::npos);
  EXPECT_NE(reason(root / "home/user").find("home folder"), std::string::npos);
  EXPECT_NE(reason(root / "home/user/work").find("working directory"), std::string::npos);
}

TEST_F(FakeRoot, NewFolderIsAcceptedAndForeignContentRefused)
{
  const fs::path out = root / "home/user/work/out";
  EXPECT_FALSE(refused(out));
  touch(out / "thesis.tex");
  EXPECT_NE(reason(out).find("not empty"), std::string::npos);
  rules.force = true; // --force never takes a non-empty folder
  EXPECT_TRUE(refused(out));
}

TEST_F(FakeRoot, EmptyFolderNeedsForceAndFileIsRefused)
{
  const fs::path empty = root / "home/user/work/empty";
  fs::create_directories(empty);
  EXPECT_NE(reason(empty).find("--force"), std::string::npos);
  rules.force = true;
  EXPECT_FALSE(refused(empty));
  touch(root / "home/user/work/file");
  EXPECT_NE(reason(root / "home/user/work/file").find("is a file"), std::string::npos);
}

TEST_F(FakeRoot, FolderHoldingAnInputIsRefused)
{
  touch(root / "home/user/work/p/in/case.toml");
  rules.inputs = {root / "home/user/work/p/in/case.toml"};
  EXPECT_NE(reason(root / "home/user/work/p").find("input file"), std::string::npos);
  EXPECT_NE(reason(root / "home/user/work/p/in").find("input file"), std::string::npos);
  EXPECT_FALSE(refused(root / "home/user/work/p/other"));
}

TEST_F(FakeRoot, MarkedFolderIsReplacedOnlyWithNothingForeign)
{
  const fs::path out = root / "home/user/work/res";
  touch(out / "summary.json");
  touch(out / "sub/a.json");
  write_marker(out, "complete");
  EXPECT_FALSE(refused(out)) << reason(out);
  touch(out / "sub/notes.txt");
  EXPECT_NE(reason(out).find("sub/notes.txt"), std::string::npos) << reason(out);
  fs::remove(out / "sub/notes.txt");
  write_marker(out, "staging");
  EXPECT_NE(reason(out).find("not a finished"), std::string::npos);
}

TEST_F(FakeRoot, ResultsHoldingNestedResultsAreReplaceable)
{
  // A plan or a sweep writes each surgery as a result folder of its own
  // inside its result: the outer marker lists the inner markers.
  const fs::path out = root / "home/user/work/plan";
  touch(out / "right/summary.json");
  write_marker(out / "right", "complete");
  touch(out / "plan.json");
  write_marker(out, "complete");
  EXPECT_FALSE(refused(out)) << reason(out);
  EXPECT_NE(read_marker(out)["files"].dump().find("right/.breastsim-result"), std::string::npos);
}

TEST_F(FakeRoot, PathsAreNormalised)
{
  const fs::path w = root / "home/user/work";
  EXPECT_EQ(normalise_path((w / "a/").string()), w / "a");
  EXPECT_EQ(normalise_path((w / "a/../b//").string()), w / "b");
  fs::create_directories(w / "real");
  fs::create_symlink(w / "real", w / "link");
  EXPECT_EQ(normalise_path((w / "link/").string()), w / "real");
  EXPECT_THROW(normalise_path(""), InputError);
  EXPECT_EQ(staging_path(w / "out", 42), w / "out.partial-42"); // a sibling, never inside
}

TEST_F(FakeRoot, StaleStagingOfDeadProcessesOnlyIsRemoved)
{
  const fs::path w = root / "home/user/work";
  const fs::path live = staging_path(w / "out", getpid());
  fs::create_directories(live);
  write_marker(live, "staging"); // this process: alive
  const fs::path unmarked = staging_path(w / "out", 1);
  touch(unmarked / "user.txt");
  // A dead process: a marker with the pid of a child that has exited.
  const pid_t child = fork();
  if (child == 0)
    _exit(0);
  waitpid(child, nullptr, 0);
  const fs::path dead = staging_path(w / "out", child);
  fs::create_directories(dead);
  write_marker(live, "staging");
  {
    std::ifstream in(live / result_marker);
    auto m = nlohmann::json::parse(in);
    m["pid"] = child;
    std::ofstream(dead / result_marker) << m.dump();
  }
  EXPECT_EQ(remove_stale_staging(w / "out"), 1);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(unmarked / "user.txt"));
}

TEST_F(FakeRoot, SecondClaimOfTheSameTargetIsRefusedWhileTheFirstHoldsIt)
{
  rules.protect = ProtectedPaths::of_this_process();
  const fs::path out = root / "home/user/work/locked";
  auto first = OutputTarget::claim(out.string(), rules, MPI_COMM_WORLD);
  try
  {
    OutputTarget::claim(out.string(), rules, MPI_COMM_WORLD);
    FAIL() << "second claim accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("another breastsim run"), std::string::npos) << e.what();
  }
}

TEST_F(FakeRoot, CommitReplacesTheOldResultAndWritesTheMarker)
{
  rules.protect = ProtectedPaths::of_this_process();
  const fs::path out = root / "home/user/work/result";
  for (int run = 0; run < 2; ++run)
  {
    auto target = OutputTarget::claim(out.string(), rules, MPI_COMM_WORLD);
    OutputDir dir(target, MPI_COMM_WORLD);
    EXPECT_EQ(dir.path().parent_path(), out.parent_path());
    write_text(dir.path() / ("run" + std::to_string(run) + ".txt"), "x", MPI_COMM_WORLD);
    dir.commit();
  }
  EXPECT_TRUE(fs::exists(out / "run1.txt"));
  EXPECT_FALSE(fs::exists(out / "run0.txt"));
  const auto m = read_marker(out);
  EXPECT_EQ(m["state"], "complete");
  EXPECT_EQ(m["files"], nlohmann::json::array({"run1.txt"}));
  for (const auto& e : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
}

TEST(CaseName, IsASafeFileNameComponent)
{
  for (const std::string bad : std::vector<std::string>{"", ".", "..", "../../etc", "a/b", "a\\b", std::string("a\0b", 3),
                                std::string("tab\there"), std::string(101, 'x')})
  {
    Config c;
    c.set("case.name", bad);
    try
    {
      c.validate();
      ADD_FAILURE() << "accepted case.name '" << bad << "'";
    }
    catch (const InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find("case.name"), std::string::npos) << e.what();
    }
  }
  Config c;
  c.set("case.name", std::string(100, 'x'));
  EXPECT_NO_THROW(c.validate());
}

TEST(ResolvedToml, StringsWithQuotesBackslashesAndNewlinesReadBack)
{
  Config c;
  c.set("case.name", std::string("say \"hi\" # not a comment"));
  c.set("solver.petsc_options", std::string("-a \"b\" C:\\temp\nline2"));
  c.set("tissue.mu", 1234.5678901234567);
  const fs::path f = fs::temp_directory_path() / ("breastsim_resolved_" + std::to_string(getpid()) + ".toml");
  std::ofstream(f) << c.to_toml();
  const Config back = Config::from_file(f);
  fs::remove(f);
  EXPECT_EQ(back.text("case.name"), c.text("case.name"));
  EXPECT_EQ(back.text("solver.petsc_options"), c.text("solver.petsc_options"));
  EXPECT_EQ(back.number("tissue.mu"), c.number("tissue.mu"));
  EXPECT_EQ(back.to_toml(), c.to_toml());
}

TEST(SizeEstimate, DefaultCaseAndTheFinestAllowedMesh)
{
  // The default case meshes to 3174 tetrahedra.
  const auto d = estimate_size(0.07, 0.06, 0.008, 1, 0);
  EXPECT_GT(d.cells, 0.7 * 3174);
  EXPECT_LT(d.cells, 1.5 * 3174);
  Config c;
  c.set("geometry.mesh_size", 0.0002);
  EXPECT_THROW(c.validate(), InputError);
}

TEST(SweepValues, EachKeyIsParsedAsItsOwnType)
{
  const Config c;
  const auto orders = sweep_values(c, "geometry.order", "1,2");
  ASSERT_EQ(orders.size(), 2u);
  EXPECT_EQ(std::get<std::int64_t>(orders[1]), 2);
  const auto fixed = sweep_values(c, "base.fixed", "true,false");
  EXPECT_TRUE(std::get<bool>(fixed[0]));
  EXPECT_FALSE(std::get<bool>(fixed[1]));
  EXPECT_DOUBLE_EQ(std::get<double>(sweep_values(c, sweep_key("a"), "35")[0]), 35.0);
  EXPECT_EQ(plain_text(fixed[0]), "true");
  EXPECT_THROW(sweep_values(c, "geometry.order", "1,1e30"), InputError);
  EXPECT_THROW(sweep_key("postures.names"), InputError);
  EXPECT_THROW(sweep_key("case.name"), InputError);
}
