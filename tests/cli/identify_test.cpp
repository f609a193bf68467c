// SPDX-License-Identifier: MIT
// `frictopt identify` on cases it cannot identify (docs/identification.md, "The measurement file"
// and "Limits"): a contact surface whose nodes a [[constraint]] fixes and the PETSc engine (both
// segmentation faults before they were refused, exit 2), and a measurement located at a fixed
// node of the contact surface (silently fitted to a neighbour before). Several experiments with
// inline measurements (cases3d/identify-lay): the joint fit, one experiment alone, no
// measurements at all, and synthetic data per experiment.
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

// cases3d/identify-lay copied into `dir`; `keep_across` false drops the second experiment.
fs::path copy_lay_case(const fs::path& dir, bool keep_across = true) {
  fs::create_directories(dir);
  std::string text = read_text(FRICTOPT_SOURCE_DIR "/cases3d/identify-lay/case.toml");
  if (!keep_across) text = text.substr(0, text.find("# Sliding across the lay"));
  std::ofstream(dir / "case.toml") << text;
  return dir / "case.toml";
}

TEST(CliIdentify, TwoExperimentsInlineRecoverBothCoefficientsOneAloneCannot) {
  const fs::path dir = fresh_directory("cli_identify_lay");
  const fs::path out = dir / "out";
  const RunResult r = run("identify " + std::string(FRICTOPT_SOURCE_DIR) + "/cases3d/identify-lay/case.toml -o " +
                          out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("4 measurements, 2 parameters, 2 experiments"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mu_x = 0.25 ±"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mu_y = 0.4 ±"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\nalong "), std::string::npos) << r.output;   // the experiments' residual lines
  EXPECT_NE(r.output.find("\nacross "), std::string::npos) << r.output;
  const std::string summary = read_text(out / "summary.json");
  EXPECT_NE(summary.find("\"experiments\""), std::string::npos);
  EXPECT_NE(summary.find("\"rms_residual\""), std::string::npos);
  const std::string fit = read_text(out / "fit.csv");
  EXPECT_EQ(fit.substr(0, fit.find('\n')), "quantity,node,x1,x2,measured,sigma,fitted,normalized_residual,experiment");
  EXPECT_NE(fit.find(",along\n"), std::string::npos) << fit;
  EXPECT_NE(fit.find(",across\n"), std::string::npos) << fit;

  // Sliding along the lay alone: μ across is not determined.
  const fs::path along = copy_lay_case(dir / "along", false);
  const RunResult a = run("identify " + along.string() + " -o " + (dir / "along" / "out").string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("mu_x = 0.25 ±"), std::string::npos) << a.output;
  EXPECT_NE(a.output.find("mu_y = 0.29"), std::string::npos) << a.output;  // near the guess 0.3
  EXPECT_NE(a.output.find("(not_determined)"), std::string::npos) << a.output;
  EXPECT_EQ(a.output.find("\nacross "), std::string::npos) << a.output;
}

TEST(CliIdentify, NoMeasurementsAnywhereIsExit2NamingTheWays) {
  const fs::path dir = fresh_directory("cli_identify_no_measurements");
  fs::create_directories(dir);
  std::string text = read_text(FRICTOPT_SOURCE_DIR "/cases3d/identify-anisotropic/case.toml");
  text.replace(text.find("measurements = \"measurements.csv\"\n"), std::string("measurements = \"measurements.csv\"\n").size(), "");
  std::ofstream(dir / "case.toml") << text;
  const RunResult r = run("identify " + (dir / "case.toml").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("case.toml: [identification] gives no measurements; expected measurements = \"file.csv\""),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CliIdentify, SyntheticDataAreWrittenPerExperimentAndFitBack) {
  const fs::path dir = fresh_directory("cli_identify_lay_synthetic");
  const fs::path case_path = copy_lay_case(dir);
  const RunResult g = run("identify " + case_path.string() + " --generate-synthetic --noise-free -o " +
                          (dir / "gen").string());
  ASSERT_EQ(g.exit_code, 0) << g.output;
  for (const char* name : {"along.csv", "across.csv"}) {
    const std::string csv = read_text(dir / "gen" / name);
    EXPECT_EQ(csv.rfind("# synthetic: frictopt identify case.toml --generate-synthetic --seed 1 --noise-free; "
                        "experiment ",
                        0),
              0u)
        << csv;
    EXPECT_NE(csv.find("mu_x = 0.25, mu_y = 0.4"), std::string::npos) << csv;
  }
  // The generated values are the committed inline ones (the example's data are reproducible).
  const std::string along = read_text(dir / "gen" / "along.csv");
  const std::string case_text = read_text(case_path);
  const auto first_value = [](const std::string& csv) {
    const std::string row = csv.substr(csv.find("total_normal_force,all,") + 23);
    return row.substr(0, row.find(','));
  };
  EXPECT_NE(case_text.find("value = " + first_value(along) + " "), std::string::npos) << first_value(along);
}

}  // namespace
