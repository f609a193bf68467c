// SPDX-License-Identifier: MIT
// Smoke test of the shipped study cases (cases2d/, cases3d/): each parses and `frictopt solve`s
// on a coarsened copy (the [mesh] cells line replaced by a small grid), and a short 2D
// `frictopt optimize` run writes its history, summary and VTK series, continues with --resume
// (the history gains rows) and refuses an existing run directory without --resume/--force.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
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

/// The log file is per test and process (common/cli_runner.hpp): the three tests here run in
/// parallel under ctest -j, and one shared log once interleaved their outputs.
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = frictopt::testing::fresh_directory("studies_" + name);
  fs::create_directories(dir);
  return dir;
}

/// Replaces the first line starting with `key =` by `key = value` (the rest of the file kept).
int count_lines(const fs::path& path) {
  std::ifstream in(path);
  int n = 0;
  for (std::string row; std::getline(in, row);)
    if (!row.empty()) ++n;
  return n;
}

std::vector<fs::path> shipped_cases(const std::string& folder) {
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(fs::path(FRICTOPT_SOURCE_DIR) / folder))
    if (fs::exists(entry.path() / "case.toml")) cases.push_back(entry.path() / "case.toml");
  std::sort(cases.begin(), cases.end());
  return cases;
}

TEST(StudiesSmoke, EveryShipped2dCaseSolves) {
  const auto cases = shipped_cases("cases2d");
  ASSERT_GE(cases.size(), 4u);  // thesis-body and ex521–ex523
  for (const fs::path& c : cases) {
    SCOPED_TRACE(c.string());
    const std::string name = c.parent_path().filename().string();
    // The 2D cases are the thesis' 450-node mesh: fast enough as they are.
    const RunResult r = run("solve " + c.string() + " -o " + fresh_directory("solve_" + name).string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("Coulomb"), std::string::npos) << r.output;
  }
}

TEST(StudiesSmoke, EveryShipped3dCaseSolvesOnACoarsenedCopy) {
  const auto cases = shipped_cases("cases3d");
  ASSERT_GE(cases.size(), 6u);  // punch, the four punch studies and punch-large
  for (const fs::path& c : cases) {
    SCOPED_TRACE(c.string());
    const std::string name = c.parent_path().filename().string();
    const fs::path dir = fresh_directory("solve_" + name);
    const fs::path coarse = dir / (name + ".toml");
    // An imported body ([mesh] file = ...) keeps its mesh, named by its absolute path
    // since the copy lives elsewhere; the structured ones get a coarse grid.
    const std::string text = read_text(c);
    const std::smatch file = [&] {
      std::smatch m;
      std::regex_search(text, m, std::regex(R"re(^file *= *"([^"]+)")re", std::regex::multiline));
      return m;
    }();
    write_text(coarse, file.empty() ? replace_key(text, "cells", "[6, 6, 3]")
                                    : replace_key(text, "file", "\"" + (c.parent_path() / file[1].str()).string() + "\""));
    const RunResult r = run("solve " + coarse.string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "out" / "summary.json")) << r.output;
  }
}

TEST(StudiesSmoke, ShortOptimizeRunWritesOutputsResumesAndRefusesAnExistingRun) {
  const fs::path dir = fresh_directory("optimize");
  const fs::path case_path = dir / "ex521.toml";
  std::string text = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "cases2d/ex521-target-pressure/case.toml");
  text = replace_key(text, "max_iterations", "3");
  text = replace_key(text, "every", "1");
  text = replace_key(text, "name", "\"smoke\"");
  write_text(case_path, text);
  const fs::path out = dir / "run";

  const RunResult first = run("optimize " + case_path.string() + " -o " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  for (const char* file : {"history.csv", "summary.json", "checkpoint.json", "final_design.json", "smoke.pvd",
                           "smoke_iter0000.vtu", "case.toml"})
    EXPECT_TRUE(fs::exists(out / file)) << file << "\n" << first.output;
  const int rows_first = count_lines(out / "history.csv");
  EXPECT_EQ(rows_first, 1 + 3);  // header + one row per iteration
  const auto summary = frictopt::io::parse_json(read_text(out / "summary.json"));
  EXPECT_EQ(summary.at("iterations").as_number(), 3);
  EXPECT_EQ(summary.at("stopped_by").as_string(), "max_iterations");
  EXPECT_LE(summary.at("final_cost").as_number(), summary.at("initial_cost").as_number());

  const double checkpoint_elapsed =
      frictopt::io::parse_json(read_text(out / "checkpoint.json")).at("run").at("elapsed_seconds").as_number();

  // An existing run is refused without --resume or --force (exit code 2, invalid input).
  const RunResult refused = run("optimize " + case_path.string() + " -o " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--resume"), std::string::npos) << refused.output;
  EXPECT_EQ(count_lines(out / "history.csv"), rows_first);

  // --resume continues from the checkpoint with the run's own case copy; allow 2 more iterations.
  write_text(out / "case.toml", replace_key(read_text(out / "case.toml"), "max_iterations", "5"));
  const RunResult resumed = run("optimize " + case_path.string() + " -o " + out.string() + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming at iteration 3"), std::string::npos) << resumed.output;
  EXPECT_EQ(count_lines(out / "history.csv"), rows_first + 2);
  const auto resumed_summary = frictopt::io::parse_json(read_text(out / "summary.json"));
  EXPECT_EQ(resumed_summary.at("iterations").as_number(), 5);
  // Counters continue over the resume (history.csv's and summary.json's alike).
  EXPECT_GT(resumed_summary.at("state_solves").as_number(), summary.at("state_solves").as_number());
  // The resumed run starts from the checkpoint's elapsed time (the first run's summary.json
  // also counts its work after the last checkpoint, which the resumed run does not repeat, so
  // comparing with it would depend on the machine's load).
  EXPECT_GT(resumed_summary.at("elapsed_seconds").as_number(), checkpoint_elapsed);

  // --force replaces the run.
  const RunResult forced = run("optimize " + case_path.string() + " -o " + out.string() + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_EQ(count_lines(out / "history.csv"), rows_first);
}

// The run solves its copy RUN/case.toml, but output names follow the user's case file: the
// default output.name is the case's stem, not the run directory's name (a run in
// "demo-output" once wrote demo-output.pvd instead of the case's name).
TEST(StudiesSmoke, OptimizeNamesItsOutputsAfterTheCaseNotTheRunDirectory) {
  const fs::path dir = fresh_directory("output_name");
  const fs::path case_path = dir / "ex521.toml";
  std::string text = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "cases2d/ex521-target-pressure/case.toml");
  text = replace_key(text, "max_iterations", "1");
  text = std::regex_replace(text, std::regex(R"(^name *=[^\n]*\n)", std::regex::multiline), "");
  write_text(case_path, text);
  const fs::path out = dir / "some-run";
  const RunResult result = run("optimize " + case_path.string() + " -o " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(fs::exists(out / "ex521.pvd")) << result.output;
  EXPECT_TRUE(fs::exists(out / "ex521_iter0000.vtu")) << result.output;
  EXPECT_FALSE(fs::exists(out / "some-run.pvd"));
}

}  // namespace

namespace {

// The orientation case through the CLI on a coarsened copy — optimize writes φ,
// a resumed run repeats the uninterrupted one bit for bit, certify and check-gradient report
// the φ component, and a law without an orientation that matters is refused with exit code 2.
TEST(StudiesSmoke, OrientationDesignThroughTheCommandLine) {
  const fs::path dir = fresh_directory("orientation");
  std::string text = read_text(fs::path(FRICTOPT_SOURCE_DIR) / "cases3d/punch-orientation/case.toml");
  text = replace_key(replace_key(text, "cells", "[6, 6, 3]"), "max_iterations", "6");
  const fs::path full = dir / "full.toml", part = dir / "part.toml";
  write_text(full, text);
  write_text(part, replace_key(text, "max_iterations", "3"));
  const RunResult a = run("optimize " + full.string() + " -o " + (dir / "a").string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(run("optimize " + part.string() + " -o " + (dir / "b").string()).exit_code, 0);
  write_text(dir / "b" / "case.toml", replace_key(read_text(dir / "b" / "case.toml"), "max_iterations", "6"));
  const RunResult b = run("optimize " + part.string() + " -o " + (dir / "b").string() + " --resume");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto sa = frictopt::io::parse_json(read_text(dir / "a" / "summary.json"));
  const auto sb = frictopt::io::parse_json(read_text(dir / "b" / "summary.json"));
  EXPECT_EQ(sa.at("final_cost").as_number(), sb.at("final_cost").as_number());
  EXPECT_EQ(sa.at("friction_orientation_deg").as_number(), sb.at("friction_orientation_deg").as_number());
  EXPECT_EQ(sa.at("initial_friction_orientation_deg").as_number(), 10.0);
  EXPECT_LT(sa.at("final_cost").as_number(), sa.at("initial_cost").as_number());
  const std::string history = read_text(dir / "a" / "history.csv");
  EXPECT_NE(history.substr(0, history.find('\n')).find(",friction_orientation_deg"), std::string::npos) << history;

  const RunResult certified = run("certify " + (dir / "a").string());
  EXPECT_TRUE(certified.exit_code == 0 || certified.exit_code == 3) << certified.output;
  EXPECT_NE(certified.output.find("17 design variables"), std::string::npos) << certified.output;
  EXPECT_NE(certified.output.find("friction orientation"), std::string::npos) << certified.output;
  const RunResult checked = run("check-gradient " + full.string() + " --step 1e-6");
  EXPECT_EQ(checked.exit_code, 0) << checked.output;
  EXPECT_NE(checked.output.find("component 16 is the friction orientation"), std::string::npos) << checked.output;

  // The [contact.friction] kind (the first "kind =" line) as an exact disc: Θ does not depend on φ.
  const fs::path disc = dir / "disc.toml";
  write_text(disc, replace_key(replace_key(text, "kind", "\"disc_exact\""), "mu_vertices", "[]"));
  write_text(disc, std::regex_replace(read_text(disc), std::regex(R"(mu_vertices = \[\])"), "mu = 0.3"));
  const RunResult refused = run("check-gradient " + disc.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("friction_orientation"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("isotropic"), std::string::npos) << refused.output;
}

}  // namespace
