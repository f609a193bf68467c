// SPDX-License-Identifier: MIT
// `frictopt identify` on cases it cannot identify (docs/identification.md, "The measurement file"
// and "Limits"): a contact surface whose nodes a [[constraint]] fixes and the PETSc engine (both
// segmentation faults before they were refused, exit 2), and a measurement located at a fixed
// node of the contact surface (silently fitted to a neighbour before).
#include <gtest/gtest.h>

#include "common/cli_runner.hpp"

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using frictopt::testing::fresh_directory;
using frictopt::testing::read_text;
using frictopt::testing::RunResult;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

// cases3d/identify-anisotropic (a 10 × 10 contact grid, measurements at x = 0.1, 0.3, ...) copied
// into `dir`, with `extra` appended to its case.toml (or its [solver.coulomb] header replaced).
fs::path copy_identify_case(const fs::path& dir, const std::string& extra, bool before_solver = false) {
  fs::create_directories(dir);
  const std::string source = FRICTOPT_SOURCE_DIR "/cases3d/identify-anisotropic/";
  fs::copy_file(source + "measurements.csv", dir / "measurements.csv");
  std::string text = read_text(source + "case.toml");
  if (before_solver) {
    const std::string header = "[solver.coulomb]";
    text.insert(text.find(header), extra);
  } else {
    text += extra;
  }
  std::ofstream(dir / "case.toml") << text;
  return dir / "case.toml";
}

TEST(CliIdentify, ConstraintOnEveryContactNodeIsRefusedWhileSolveAcceptsIt) {
  const fs::path dir = fresh_directory("cli_identify_pinned_bottom");
  const fs::path case_path = copy_identify_case(dir, "\n[[constraint]]\nboundary = \"bottom\"\ncomponents = [2]\n");
  const RunResult r = run("identify " + case_path.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;  // was 139 (resolve_measurements on no contact node)
  EXPECT_NE(r.output.find("the contact surface \"bottom\" has no contact node: each of its 121 nodes has a "
                          "component fixed by a [[dirichlet]] table or a [[constraint]] (constraint[0] fixes node 0)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // The same case is an elasticity problem without contact nodes for solve.
  const RunResult solved = run("solve " + case_path.string() + " -o " + (dir / "solved").string());
  EXPECT_EQ(solved.exit_code, 0) << solved.output;
}

TEST(CliIdentify, MeasurementAtAConstrainedContactNodeIsRefused) {
  const fs::path dir = fresh_directory("cli_identify_pinned_node");
  const fs::path case_path = copy_identify_case(
      dir, "\n[[constraint]]\nbox_min = [0.05, 0.05, -0.1]\nbox_max = [0.15, 0.15, 0.1]\ncomponents = [2]\n");
  const RunResult r = run("identify " + case_path.string() + " -o " + (dir / "out").string());
  // Was exit 0: the measurement at (0.1, 0.1) was fitted to the contact node at (0.1, 0).
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("measurements.csv:3: location (0.1, 0.1) is nearest to mesh node 12 at (0.1, 0.1), which "
                          "constraint[0] fixes: a support, not a contact node"),
            std::string::npos)
      << r.output;
}

TEST(CliIdentify, PetscEngineIsRefusedBeforeAnySolve) {
  const fs::path dir = fresh_directory("cli_identify_petsc");
  const fs::path case_path = copy_identify_case(dir, "[solver]\nengine = \"petsc\"\n\n", true);
  const RunResult r = run("identify " + case_path.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;  // was a SEGV in DenseDelassus::size() (PETSc's handler: 59)
  EXPECT_NE(r.output.find("[solver] engine = \"petsc\": identification needs the direct engine"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
