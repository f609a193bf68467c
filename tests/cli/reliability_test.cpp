// SPDX-License-Identifier: MIT
// Reproducers of the "nothing lost, nothing silent" guarantees, end to end through the
// command line: each gives a clean, documented outcome (README "Command line", docs/case-
// format.md "Run directories", "Size limits", "Physical bounds"), never a crash, never a
// deleted or overwritten file frictopt did not write.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "common/cli_runner.hpp"
#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::read_text;
using frictopt::testing::replace_key;
using frictopt::testing::write_text;
using frictopt::testing::RunResult;

RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

fs::path fresh(const std::string& name) {
  const fs::path dir = frictopt::testing::fresh_directory("reliability_" + name);
  fs::create_directories(dir);
  return dir;
}

// The thesis' example 5.2.1 (2D, 450 nodes): a 12-iteration run takes well under a second.
std::string ex521(int max_iterations) {
  std::string text = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "cases2d/ex521-target-pressure/case.toml");
  text = replace_key(text, "max_iterations", std::to_string(max_iterations));
  text = replace_key(text, "every", "2");
  return replace_key(text, "name", "\"r\"");
}

std::string small3d() { return read_text(fs::path(FRICTOPT_SOURCE_DIR) / "tests/cli/data/small3d.toml"); }

void expect_refused(const RunResult& r, std::initializer_list<std::string_view> fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (std::string_view f : fragments) EXPECT_NE(r.output.find(f), std::string::npos) << "'" << f << "' not in:\n" << r.output;
}

// --- Data loss and damage (items 1–4) -----------------------------------------------------

TEST(Reliability, ForceRefusesADirectoryWithForeignEntriesAndRemovesNothing) {
  const fs::path dir = fresh("force");
  write_text(dir / "case.toml", ex521(2));
  ASSERT_EQ(run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string()).exit_code, 0);
  write_text(dir / "run" / "precious.txt", "keep");
  const RunResult r = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string() + " --force");
  expect_refused(r, {"precious.txt", "nothing was removed"});
  EXPECT_EQ(read_text(dir / "run" / "precious.txt"), "keep");
  EXPECT_TRUE(fs::exists(dir / "run" / "history.csv"));

  // "-o ." with the case and an unrelated folder in it: refused, the case and the folder stay.
  fs::create_directories(dir / "notes");
  write_text(dir / "notes" / "a.txt", "keep");
  const RunResult here = run("optimize " + (dir / "case.toml").string() + " -o " + dir.string() + " --force");
  expect_refused(here, {"notes/", "run/"});
  EXPECT_TRUE(fs::exists(dir / "case.toml"));
  EXPECT_TRUE(fs::exists(dir / "notes" / "a.txt"));
}

TEST(Reliability, ForceReplacesARunOfOurFilesOnly) {
  const fs::path dir = fresh("force_ok");
  write_text(dir / "case.toml", ex521(2));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  ASSERT_EQ(run("certify " + (dir / "run").string()).exit_code, 0);
  const RunResult r = run(args + " --force");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "run" / "certificate.json"));  // the old run's file, removed
}

TEST(Reliability, ALinkedOutputFileIsRefusedAndItsTargetUntouched) {
  const fs::path dir = fresh("symlink");
  write_text(dir / "case.toml", ex521(2));
  ASSERT_EQ(run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string()).exit_code, 0);
  write_text(dir / "elsewhere.json", "keep");
  fs::create_symlink(dir / "elsewhere.json", dir / "run" / "certificate.json");
  expect_refused(run("certify " + (dir / "run").string()), {"certificate.json", "symbolic link"});
  EXPECT_EQ(read_text(dir / "elsewhere.json"), "keep");
  EXPECT_TRUE(fs::is_symlink(dir / "run" / "certificate.json"));
}

TEST(Reliability, ASecondRunIntoALockedDirectoryIsRefused) {
  const fs::path dir = fresh("lock");
  write_text(dir / "case.toml", ex521(2));
  fs::create_directories(dir / "run");
  // This test process holds the lock, as a first `frictopt optimize` would.
  const int fd = ::open((dir / "run" / ".frictopt.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const RunResult r = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string());
  ::close(fd);
  expect_refused(r, {"in use by another frictopt process"});
  EXPECT_FALSE(fs::exists(dir / "run" / "history.csv"));
  EXPECT_EQ(run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string()).exit_code, 0);
}

TEST(Reliability, ResumeRefusesAnotherProblemNamingWhatChanged) {
  const fs::path dir = fresh("resume_mismatch");
  const fs::path case_path = dir / "case.toml", out = dir / "run";
  write_text(case_path, ex521(2));
  ASSERT_EQ(run("optimize " + case_path.string() + " -o " + out.string()).exit_code, 0);

  write_text(dir / "other.toml", replace_key(ex521(2), "mu", "0.4"));
  expect_refused(run("optimize " + (dir / "other.toml").string() + " -o " + out.string() + " --resume"),
                 {"contact.friction.mu: 0.25 -> 0.4"});
  write_text(dir / "three.toml", small3d() + "\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\n[cost]\nkind = \"compliance\"\n");
  expect_refused(run("optimize " + (dir / "three.toml").string() + " -o " + out.string() + " --resume"),
                 {"geometry.dim: 2 -> 3"});
  expect_refused(run("optimize " + (dir / "missing.toml").string() + " -o " + out.string() + " --resume"),
                 {"missing.toml", "does not exist"});
  // An edited copy in the run directory: the checkpoint's fingerprint names the change.
  const std::string original = read_text(out / "case.toml");
  write_text(out / "case.toml", replace_key(original, "cells", "[28, 14]"));
  expect_refused(run("optimize " + (out / "case.toml").string() + " -o " + out.string() + " --resume"),
                 {"mesh.cells: [29, 14] -> [28, 14]", "the mesh"});
  write_text(out / "case.toml", original);
  // Only [optimization] and [output] may change: a longer run of the same problem resumes.
  write_text(out / "case.toml", replace_key(original, "max_iterations", "3"));
  EXPECT_EQ(run("optimize " + case_path.string() + " -o " + out.string() + " --resume").exit_code, 0);
}

TEST(Reliability, CheckpointCountersOutOfRangeAreRefused) {
  const fs::path dir = fresh("checkpoint_range");
  write_text(dir / "case.toml", ex521(2));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  const std::string checkpoint = read_text(dir / "run" / "checkpoint.json");
  for (const std::string value : {"-5", "1000000000000"}) {
    write_text(dir / "run" / "checkpoint.json",
               std::regex_replace(checkpoint, std::regex(R"("iteration": \d+)"), "\"iteration\": " + value));
    expect_refused(run(args + " --resume"), {"checkpoint.json", "iteration = " + value});
  }
}

TEST(Reliability, AResumedRunRepeatsTheUninterruptedOneBitForBit) {
  // Item 11: the checkpoint holds the method's whole state and the contact warm start, so the
  // resumed run's designs, costs and history (but its timings) equal the uninterrupted run's.
  const fs::path dir = fresh("resume_identical");
  write_text(dir / "full.toml", ex521(12));
  write_text(dir / "part.toml", ex521(5));
  ASSERT_EQ(run("optimize " + (dir / "full.toml").string() + " -o " + (dir / "a").string()).exit_code, 0);
  ASSERT_EQ(run("optimize " + (dir / "part.toml").string() + " -o " + (dir / "b").string()).exit_code, 0);
  write_text(dir / "b" / "case.toml", replace_key(read_text(dir / "b" / "case.toml"), "max_iterations", "12"));
  const RunResult resumed = run("optimize " + (dir / "b" / "case.toml").string() + " -o " + (dir / "b").string() + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const auto a = frictopt::io::parse_json(read_text(dir / "a" / "summary.json"));
  const auto b = frictopt::io::parse_json(read_text(dir / "b" / "summary.json"));
  ASSERT_EQ(a.at("iterations").as_integer(), 12);
  EXPECT_EQ(a.at("alpha"), b.at("alpha"));
  EXPECT_EQ(a.at("final_cost").as_number(), b.at("final_cost").as_number());
  EXPECT_EQ(a.at("state_solves").as_integer(), b.at("state_solves").as_integer());
  // history.csv without the timing columns (the last three).
  const auto without_timings = [](const std::string& csv) {
    return std::regex_replace(csv, std::regex(R"(,[^,\n]*,[^,\n]*,[^,\n]*\n)"), "\n");
  };
  EXPECT_EQ(without_timings(read_text(dir / "a" / "history.csv")), without_timings(read_text(dir / "b" / "history.csv")));
}

// --- Crashes and sizes (items 5–7) --------------------------------------------------------

TEST(Reliability, OneCellLayerUnderAFullyFixedTopIsRefused) {
  const fs::path dir = fresh("one_layer");
  std::string text = replace_key(small3d(), "cells", "[4, 4, 1]");
  text = std::regex_replace(text, std::regex(R"(\[\[load\]\]\nface = "top"\ntraction = [^\n]*\n)"), "");
  text = replace_key(text, "face", "\"top\"");
  write_text(dir / "a.toml", text + "\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\n");
  expect_refused(run("solve " + (dir / "a.toml").string() + " -o " + (dir / "out").string()),
                 {"mesh.cells = [4, 4, 1]", "no free unknown"});
  std::string two = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "cases2d/ex521-target-pressure/case.toml");
  two = std::regex_replace(two, std::regex(R"(\[\[load\]\]\nface = "top"\ntraction = [^\n]*\n)"), "");
  two = replace_key(replace_key(two, "cells", "[29, 1]"), "face", "\"top\"");
  write_text(dir / "b.toml", two);
  expect_refused(run("solve " + (dir / "b.toml").string() + " -o " + (dir / "out").string()),
                 {"mesh.cells = [29, 1]", "no free unknown"});
}

TEST(Reliability, AbsurdSizesAndNearlyIncompressibleMaterialsAreRefusedAtOnce) {
  const fs::path dir = fresh("sizes");
  const std::string base = ex521(2);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {replace_key(small3d(), "cells", "[300, 300, 300]"), {"mesh.cells", "GB"}},
      {replace_key(small3d(), "control_points", "[100000, 100000]"), {"design.control_points[0] = 100000"}},
      {replace_key(base, "control_points", "[1000000]"), {"design.control_points[0] = 1000000"}},
      {replace_key(small3d(), "poisson", "0.3") + "\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\nn = 1000000\n",
       {"contact.friction.n = 1000000"}},
      {replace_key(base, "poisson", "0.49999999"), {"material.poisson = 0.49999999"}},
      {replace_key(base, "young", "1e308"), {"material.young"}},
      {replace_key(base, "young", "1e-300"), {"material.young"}},
      {std::regex_replace(small3d(), std::regex("face = \"left\""), "face = \"left\"\ndisplacement = [1e300, 0, 0]"),
       {"dirichlet[0].displacement[0]"}},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(i);
    const fs::path path = dir / ("case" + std::to_string(i) + ".toml");
    write_text(path, cases[i].first);
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = run("solve " + path.string() + " -o " + (dir / "out").string());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 2) << r.output;
    for (const std::string& f : cases[i].second) EXPECT_NE(r.output.find(f), std::string::npos) << f << "\n" << r.output;
    EXPECT_EQ(r.output.find("1410065408"), std::string::npos) << r.output;  // never a wrapped count
    EXPECT_LT(seconds, 10.0) << "refused only after " << seconds << " s";
  }
}

TEST(Reliability, FileSystemErrorsAreReportedWithTheirOwnExitCode) {
  const fs::path dir = fresh("filesystem");
  write_text(dir / "case.toml", ex521(2));
  write_text(dir / "file", "x");
  const RunResult not_a_directory = run("solve " + (dir / "case.toml").string() + " -o " + (dir / "file").string());
  expect_refused(not_a_directory, {"not a directory"});
  const RunResult below_a_file = run("solve " + (dir / "case.toml").string() + " -o " + (dir / "file" / "sub").string());
  EXPECT_EQ(below_a_file.exit_code, 5) << below_a_file.output;
  EXPECT_NE(below_a_file.output.find("error: file system"), std::string::npos) << below_a_file.output;
}

TEST(Reliability, ADamagedLastHistoryRowAndAStrayVtuAreToleratedOnResume) {
  const fs::path dir = fresh("damaged_history");
  write_text(dir / "case.toml", ex521(4));
  const std::string args = "optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string();
  ASSERT_EQ(run(args).exit_code, 0);
  write_text(dir / "run" / "case.toml", replace_key(read_text(dir / "run" / "case.toml"), "max_iterations", "6"));
  std::ofstream(dir / "run" / "history.csv", std::ios::app) << "5,7,seri";  // a write cut short by a kill
  write_text(dir / "run" / "r_iterXYZW.vtu", "not ours");
  const RunResult r = run(args + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("incomplete"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("r_iterXYZW.vtu"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(dir / "run" / "r_iterXYZW.vtu"), "not ours");
  int rows = 0;
  std::ifstream history(dir / "run" / "history.csv");
  for (std::string line; std::getline(history, line);) rows += !line.empty();
  EXPECT_EQ(rows, 1 + 6);
}

// --- Silent or inconsistent (items 8–10) --------------------------------------------------

TEST(Reliability, UsageErrorsExitTwo) {
  EXPECT_EQ(run("solve").exit_code, 2);                           // missing argument (CLI11: 106)
  EXPECT_EQ(run("solve a b c").exit_code, 2);                     // extra arguments
  EXPECT_EQ(run("solve --no-such-option x").exit_code, 2);        // unknown option (109)
  EXPECT_EQ(run("frobnicate").exit_code, 2);                      // unknown subcommand
  EXPECT_EQ(run("--help").exit_code, 0);
  const std::string c = FRICTOPT_SOURCE_DIR "/cases2d/ex521-target-pressure/case.toml";
  expect_refused(run("check-gradient " + c + " --step nan"), {"not a finite number"});
  expect_refused(run("check-gradient " + c + " --step 1"), {"--step"});  // out of range (105)
}

TEST(Reliability, CheckGradientRefusesADesignOutsideTheAdmissibleSetLikeCertify) {
  const fs::path dir = fresh("design_outside");
  write_text(dir / "design.json", "{\"alpha\": [0.05,0.05,0.05,0.05,0.05,0.05,0.05,0.9,0.05,0.05,0.05,0.05,0.05,0.05,0.05]}");
  expect_refused(run("check-gradient " FRICTOPT_SOURCE_DIR "/cases2d/ex521-target-pressure/case.toml --design " +
                     (dir / "design.json").string()),
                 {"design.json", "violates the admissible set"});
}

TEST(Reliability, AnIterationLimitFailsWithExitThreeFromSolveAndOptimize) {
  const fs::path dir = fresh("iteration_limit");
  write_text(dir / "case.toml", ex521(2) + "\n[solver.coulomb]\nmax_iterations = 1\n");
  const RunResult solve = run("solve " + (dir / "case.toml").string() + " -o " + (dir / "s").string());
  const RunResult optimize = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "o").string());
  EXPECT_EQ(solve.exit_code, 3) << solve.output;
  EXPECT_EQ(optimize.exit_code, 3) << optimize.output;
  EXPECT_NE(optimize.output.find("max_iterations = 1 reached"), std::string::npos) << optimize.output;
  // solve's summary.json says why.
  const auto summary = frictopt::io::parse_json(read_text(dir / "s" / "summary.json"));
  EXPECT_EQ(summary.at("status").as_string(), "max_iterations");
}

TEST(Reliability, OutputNamesEmptyFilesAndLoadsOnFixedFacesAreReported) {
  const fs::path dir = fresh("case_items");
  write_text(dir / "nul.toml", replace_key(ex521(2), "name", R"("r\u0000x")"));
  expect_refused(run("solve " + (dir / "nul.toml").string() + " -o " + (dir / "out").string()), {"output.name"});
  EXPECT_FALSE(fs::exists(dir / "out"));
  write_text(dir / "empty.toml", "");
  expect_refused(run("solve " + (dir / "empty.toml").string()), {"empty.toml: the case file is empty"});
  // A second load on the clamped left face: its traction does no work.
  write_text(dir / "fixed.toml", ex521(2) + "\n[[load]]\nface = \"left\"\ntraction = [0.0, -1.0e6]\n");
  expect_refused(run("solve " + (dir / "fixed.toml").string()), {"load[1].traction[1]", "does no work"});
}

TEST(Reliability, SolveSummaryHoldsTheContactSolveTime) {
  const fs::path dir = fresh("summary_time");
  ASSERT_EQ(run("solve " FRICTOPT_SOURCE_DIR "/cases2d/ex521-target-pressure/case.toml -o " + dir.string()).exit_code, 0);
  const auto summary = frictopt::io::parse_json(read_text(dir / "summary.json"));
  EXPECT_GT(summary.at("contact").at("time_seconds").as_number(), 0.0);
  EXPECT_GT(summary.at("contact").at("fixed_point_iterations").as_integer(), 0);
}

}  // namespace
