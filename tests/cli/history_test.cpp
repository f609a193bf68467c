// SPDX-License-Identifier: MIT
// Costs along a loading history through the command line (docs/theory/history-adjoint.md):
// check-gradient and certify read the [[program.step]] tables of the shipped press-and-drag punch,
// check-gradient the [[load_case.step]] tables of the shipped grip dragged in three directions; a
// history cost on a one-step case, a step out of range or of the wrong type, and the compliance
// with a program exit 2 naming the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/cli_runner.hpp"
#include "common/case_text.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::fresh_directory;
using frictopt::testing::RunResult;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

const std::string kCase = std::string(FRICTOPT_SOURCE_DIR) + "/cases3d/punch-press-drag/case.toml";

// The small block pressed and dragged by its top (common/case_text.hpp); `program` and `cost` are appended.
std::string block_case(const std::string& program, const std::string& cost) {
  return frictopt::testing::pressed_dragged_block_3d() + program + cost;
}

const std::string kProgram = R"(
[[program.step]]
dirichlet_scale = [1.0, 0.0]
[[program.step]]
dirichlet_scale = [1.0, 1.0]
)";

fs::path write_case(const std::string& name, const std::string& text) {
  const fs::path dir = fresh_directory("history_" + name);
  fs::create_directories(dir);
  const fs::path path = dir / "case.toml";
  std::ofstream(path) << text;
  return path;
}

void expect_invalid(const std::string& name, const std::string& text, const std::string& needle) {
  const fs::path path = write_case(name, text);
  const RunResult r = run("check-gradient " + path.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << "expected \"" << needle << "\" in:\n" << r.output;
}

TEST(HistoryCli, CheckGradientReadsTheProgram) {
  const RunResult r = run("check-gradient " + kCase);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cost dissipation"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("loading program: 3 steps"), std::string::npos) << r.output;
}

TEST(HistoryCli, CheckGradientReadsLoadCasesGivenAsPrograms) {
  // cases3d/grip-press-drag-directions: three load cases, each a three-step program.
  const RunResult r =
      run("check-gradient " + std::string(FRICTOPT_SOURCE_DIR) + "/cases3d/grip-press-drag-directions/case.toml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cost dissipation"), std::string::npos) << r.output;
  for (const char* name : {"load case drag 0 ", "load case drag 45 ", "load case drag 90 "})
    EXPECT_NE(r.output.find(name), std::string::npos) << name << " in:\n" << r.output;
  EXPECT_NE(r.output.find("backward adjoint over 3 steps"), std::string::npos) << r.output;
}

TEST(HistoryCli, OptimizeAndCertifyReadTheProgram) {
  const fs::path path = write_case(
      "optimize", block_case(kProgram, "[cost]\nkind = \"dissipation\"\n[optimization]\nmax_iterations = 2\n"));
  const fs::path out = fresh_directory("history_optimize_run");
  const RunResult optimized = run("optimize " + path.string() + " -o " + out.string());
  ASSERT_EQ(optimized.exit_code, 0) << optimized.output;
  const RunResult certified = run("certify " + out.string());
  ASSERT_EQ(certified.exit_code, 0) << certified.output;
  EXPECT_NE(certified.output.find("cost dissipation"), std::string::npos) << certified.output;
  EXPECT_NE(certified.output.find("not computed for a cost along a loading history"), std::string::npos)
      << certified.output;
  EXPECT_NE(frictopt::testing::read_text(out / "certificate.json").find("\"history_steps\""), std::string::npos);
}

TEST(HistoryCli, HistoryCostOnAOneStepCaseExits2) {
  expect_invalid("dissipation_one_step", block_case("", "[cost]\nkind = \"dissipation\"\n"),
                 "cost.kind = \"dissipation\"; expected a cost of one state");
  expect_invalid("step_one_step", block_case("", "[cost]\nkind = \"normal_force_power\"\nstep = 1\n"),
                 "cost.step = 1; expected no step: the loads are one step");
}

TEST(HistoryCli, StepOutOfRangeExits2) {
  const std::string expectation = "expected \"last\" or an integer step in [1, 2]";
  expect_invalid("step_zero", block_case(kProgram, "[cost]\nkind = \"normal_force_power\"\nstep = 0\n"),
                 "cost.step = 0; " + expectation);
  expect_invalid("step_three", block_case(kProgram, "[cost]\nkind = \"normal_force_power\"\nstep = 3\n"),
                 "cost.step = 3; " + expectation);
  expect_invalid("step_real", block_case(kProgram, "[cost]\nkind = \"normal_force_power\"\nstep = 1.5\n"),
                 "cost.step = 1.5; " + expectation);
  expect_invalid("step_word", block_case(kProgram, "[cost]\nkind = \"normal_force_power\"\nstep = \"first\"\n"),
                 "cost.step = \"first\"; " + expectation);
}

TEST(HistoryCli, ComplianceWithAProgramExits2) {
  expect_invalid("compliance", block_case(kProgram, "[cost]\nkind = \"compliance\"\n"),
                 "cost.kind = \"compliance\"; expected a contact cost (target_pressure");
}

}  // namespace
