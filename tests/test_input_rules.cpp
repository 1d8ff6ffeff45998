// SPDX-License-Identifier: LGPL-3.0-or-later
// The rules that guard user input and output at the edge: PETSc options that
// touch files, duplicate JSON keys, long values in messages, links and
// malformed markers in result folders, files written without following links.
#include "errors.hpp"
#include "input_file.hpp"
#include "output.hpp"
#include "output_target.hpp"
#include "petsc_option_rules.hpp"
#include "safe_write.hpp"
#include "strict_json.hpp"
#include "strings.hpp"
#include <fstream>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

using namespace breastsim;
namespace fs = std::filesystem;

namespace
{
std::string refusal(const std::string& options) { return petsc_options_refusal(options).value_or(""); }

struct Scratch : ::testing::Test
{
  fs::path dir;
  OutputRules rules;
  void SetUp() override
  {
    dir = fs::weakly_canonical(fs::temp_directory_path() / ("breastsim_rules_" + std::to_string(getpid())));
    fs::remove_all(dir);
    fs::create_directories(dir);
    rules.protect = {"/", "", ""};
  }
  void TearDown() override { fs::remove_all(dir); }
  static void touch(const fs::path& p, const std::string& text = "x") { std::ofstream(p) << text; }
  std::string reason(const fs::path& p) { return refusal_reason(p, rules).value_or(""); }
};
} // namespace

TEST(PetscOptionRules, SolverOptionsAndStdoutViewersPass)
{
  for (const char* ok : {"", "-ksp_type gmres -pc_type hypre", "-ksp_rtol 1e-8 -ksp_max_it -1",
                         "-mat_mumps_icntl_14 40", "-ksp_monitor", "-ksp_view ::ascii_info_detail",
                         "-log_view", "-ksp_converged_reason ascii", "-options_left 0",
                         "-pc_factor_mat_solver_type \"mumps\""})
    EXPECT_EQ(refusal(ok), "") << ok;
}

TEST(PetscOptionRules, OptionsThatTouchFilesOrProgramsAreRefusedByName)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"-log_view :/tmp/x", "-log_view"},
      {"-log_view ascii:/tmp/x", "-log_view"},
      {"-ksp_view binary", "-ksp_view"},
      {"-ksp_monitor draw", "-ksp_monitor"},
      {"-ksp_converged_reason :x.txt", "-ksp_converged_reason"},
      {"-viewer_binary_filename f.bin", "-viewer_binary_filename"},
      {"-options_file /dev/zero", "-options_file"},
      {"-options_file_yaml a.yml", "-options_file_yaml"},
      {"-history h.txt", "-history"},
      {"-malloc_dump m.txt", "-malloc_dump"},
      {"-info i.txt", "-info"},
      {"-start_in_debugger", "-start_in_debugger"},
      {"-on_error_attach_debugger gdb", "-on_error_attach_debugger"},
      {"-log_trace t", "-log_trace"},
      {"-pc_type python", "-pc_type"},
      {"-ksp_type gmres -mat_type /tmp/lib.so", "-mat_type"},
      {"stray", "'stray'"},
  };
  for (const auto& [options, named] : cases)
  {
    const std::string why = refusal(options);
    EXPECT_NE(why.find(named), std::string::npos) << options << ": " << why;
  }
}

TEST(PetscOptionRules, ValuesAndNegativeNumbersAreParsedAsPetscReadsThem)
{
  const auto o = parse_petsc_options("-a 1 -b -2.5 -c 'x y' -d");
  ASSERT_EQ(o.size(), 4u);
  EXPECT_EQ(o[1].value, "-2.5");
  EXPECT_EQ(o[2].value, "'x y'"); // whitespace-split, quotes kept inside a split value
  EXPECT_EQ(o[3].value, "");
}

TEST(StrictJson, DuplicateKeysAreRefusedAtAnyDepth)
{
  EXPECT_NO_THROW(parse_json_strict(R"({"a": 1, "b": {"a": 2}, "c": [{"a": 1}, {"a": 2}]})"));
  EXPECT_THROW(parse_json_strict(R"({"units": "mm", "units": "SI"})"), DuplicateJsonKey);
  try
  {
    parse_json_strict(R"({"p": [{"x": 1, "y": 2, "x": 3}]})");
    FAIL() << "duplicate accepted";
  }
  catch (const DuplicateJsonKey& e)
  {
    EXPECT_EQ(e.key, "x");
  }
  EXPECT_THROW(parse_json_strict("{\"a\": "), nlohmann::json::exception);
}

TEST(Messages, LongValuesAreShortenedWithTheirLength)
{
  EXPECT_EQ(shorten("abc"), "abc");
  const std::string s = shorten(std::string(100000, '7'));
  EXPECT_LT(s.size(), 120u);
  EXPECT_NE(s.find("(100000 bytes)"), std::string::npos);
}

TEST_F(Scratch, InputFilesAreDescribedByWhatTheyAre)
{
  auto why = [](const fs::path& p)
  {
    try
    {
      check_input_file(p, "case file");
      return std::string();
    }
    catch (const InputError& e)
    {
      return std::string(e.what());
    }
  };
  touch(dir / "ok.toml");
  EXPECT_EQ(why(dir / "ok.toml"), "");
  EXPECT_NE(why(dir / "missing.toml").find("does not exist"), std::string::npos);
  EXPECT_NE(why(dir).find("is a folder, not a regular file"), std::string::npos);
  fs::create_symlink("b", dir / "a");
  fs::create_symlink("a", dir / "b");
  EXPECT_NE(why(dir / "a").find("loop of symbolic links"), std::string::npos) << why(dir / "a");
  fs::create_symlink("nowhere", dir / "dangling");
  EXPECT_NE(why(dir / "dangling").find("symbolic link to nothing"), std::string::npos);
  ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0644), 0);
  EXPECT_NE(why(dir / "fifo").find("named pipe (FIFO)"), std::string::npos);
}

TEST_F(Scratch, MarkerListingAPathOutsideItsFolderIsRefusedAtOnce)
{
  for (const char* entry : {"/x", "../x", "a/../../x"})
  {
    const fs::path out = dir / "res";
    fs::create_directories(out);
    touch(out / result_marker, nlohmann::json{{"format", "breastsim result folder"},
                                              {"state", "complete"},
                                              {"files", {entry}}}
                                   .dump());
    EXPECT_NE(reason(out).find("not a path inside the folder"), std::string::npos) << entry << ": " << reason(out);
    fs::remove_all(out);
  }
}

TEST_F(Scratch, LinksInAResultFolderAreForeignEvenWhenListed)
{
  const fs::path out = dir / "res";
  fs::create_directories(out);
  touch(out / "overview.png");
  write_marker(out, "complete");
  EXPECT_EQ(reason(out), "");
  fs::remove(out / "overview.png");
  touch(dir / "elsewhere.txt", "mine");
  fs::create_symlink(dir / "elsewhere.txt", out / "overview.png");
  EXPECT_NE(reason(out).find("'overview.png', which is a symbolic link"), std::string::npos) << reason(out);
}

TEST_F(Scratch, FilesAreNeverWrittenThroughALink)
{
  touch(dir / "target.txt", "mine");
  fs::create_symlink(dir / "target.txt", dir / "link.txt");
  EXPECT_THROW(write_file_nofollow(dir / "link.txt", "overwritten"), std::system_error);
  std::ifstream in(dir / "target.txt");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "mine");
  write_file_nofollow(dir / "new.txt", "a");
  EXPECT_THROW(write_file_nofollow(dir / "new.txt", "b", Existing::refuse), std::system_error);
}

TEST_F(Scratch, LockFileThatIsALinkIsRefusedAndItsTargetNotCreated)
{
  rules.protect = ProtectedPaths::of_this_process();
  fs::create_symlink(dir / "lock-target", dir / ".out.breastsim-lock");
  try
  {
    OutputTarget::claim((dir / "out").string(), rules, MPI_COMM_WORLD);
    FAIL() << "claim accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("is a symbolic link"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "lock-target")));
}
