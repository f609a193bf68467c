// SPDX-License-Identifier: MIT
// End-to-end checks of the friction experiments' commands: `solve` of a case with a loading program
// writes one .vtu per step, a .pvd and a summary with the resultants of every step; `experiment`
// writes the tribometer CSVs; a plain `solve` reports the contact resultants; bad programs exit 2
// naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <fstream>
#include <string>

#include "common/cli_runner.hpp"
#include "common/case_text.hpp"
#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::fresh_directory;
using frictopt::testing::read_text;
using frictopt::testing::RunResult;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

// The small flat block pressed and dragged by its top (two [[dirichlet]] tables; common/case_text.hpp),
// with a tribometer and a program.
std::string block_case(const std::string& program) {
  return frictopt::testing::pressed_dragged_block_3d() + R"([experiment]
normal_force = 1.0e4
pull_displacement = 1.0e-5
angles_degrees = [0, 90]
ramp_steps = 5
)" + program;
}

fs::path write_case(const fs::path& dir, const std::string& text) {
  fs::create_directories(dir);
  const fs::path path = dir / "block.toml";
  std::ofstream(path) << text;
  return path;
}

TEST(CliProgram, WritesOneVtuPerStepAndTheResultantsOfEachStep) {
  const fs::path dir = fresh_directory("program");
  const fs::path c = write_case(dir, block_case(R"(
[[program.step]]
label = "press"
dirichlet_scale = [1.0, 0.0]
friction = false
[[program.step]]
dirichlet_scale = [1.0, 1.0]
[[program.step]]
dirichlet_scale = [1.0, 2.0]
)"));
  const RunResult r = run("solve " + c.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 factorization"), std::string::npos) << r.output;
  for (int k = 1; k <= 3; ++k)
    EXPECT_TRUE(fs::exists(dir / "out" / ("block_iter000" + std::to_string(k) + ".vtu")));
  EXPECT_TRUE(fs::exists(dir / "out" / "block.pvd"));
  const auto json = frictopt::io::parse_json(read_text(dir / "out" / "summary.json"));
  ASSERT_EQ(json.at("steps").as_array().size(), 3u);
  const auto& press = json.at("steps").as_array()[0].at("contact");
  EXPECT_GT(press.at("total_normal_force").as_number(), 0.0);
  EXPECT_EQ(press.at("total_tangential_force_norm").as_number(), 0.0);  // frictionless step
  const auto& drag = json.at("steps").as_array()[2].at("contact");
  EXPECT_GT(drag.at("tangential_to_normal_ratio").as_number(), 0.0);
  EXPECT_LE(drag.at("tangential_to_normal_ratio").as_number(), 0.3 + 1e-9);
  EXPECT_EQ(json.at("factorizations").as_integer(), 1);
}

TEST(CliProgram, PlainSolveReportsTheContactResultants) {
  const fs::path dir = fresh_directory("resultants");
  const fs::path c = write_case(dir, block_case(""));
  const RunResult r = run("solve " + c.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("contact forces: P = "), std::string::npos) << r.output;
  const auto json = frictopt::io::parse_json(read_text(dir / "out" / "summary.json"));
  const auto& contact = json.at("contact");
  for (const char* key :
       {"total_normal_force", "total_tangential_force", "tangential_to_normal_ratio",
        "contact_area", "num_stick", "num_slip", "num_separated", "stick_area", "slip_area",
        "stick_centroid", "stick_equivalent_radius", "min_initial_gap"})
    EXPECT_TRUE(contact.contains(key)) << key;
  // A flat block on the plate: every contact node is loaded; the area is the whole base.
  EXPECT_NEAR(contact.at("contact_area").as_number(), 0.01, 1e-12);
  EXPECT_EQ(contact.at("min_initial_gap").as_number(), 0.0);
}

TEST(CliExperiment, WritesThePolarAndTheRamp) {
  const fs::path dir = fresh_directory("experiment");
  const fs::path c = write_case(dir, block_case(""));
  const RunResult r = run("experiment " + c.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string polar = read_text(dir / "out" / "tribometer_polar.csv");
  EXPECT_EQ(std::count(polar.begin(), polar.end(), '\n'), 3);  // header + 2 angles
  EXPECT_TRUE(fs::exists(dir / "out" / "tribometer_ramp.csv"));
  EXPECT_TRUE(fs::exists(dir / "out" / "tribometer_law.csv"));
  const auto json = frictopt::io::parse_json(read_text(dir / "out" / "summary.json"));
  for (const auto& a : json.at("angles").as_array()) {
    ASSERT_TRUE(a.at("steady_sliding").as_bool());
    EXPECT_NEAR(a.at("measured_mu").as_number(), 0.3, 3e-7);
    EXPECT_NEAR(a.at("onset_normal_force").as_number(), 1e4, 1e-5);
  }
}

TEST(CliExperiment, BadProgramsAndExperimentsExitTwoNamingTheField) {
  const fs::path dir = fresh_directory("experiment_bad");
  struct Bad {
    std::string text, command, expected;
  };
  const std::vector<Bad> cases = {
      {block_case("[program]\n"), "solve", "program.step"},
      {block_case("[[program.step]]\nload_scale = [1.0]\n"), "solve", "program.step[0].load_scale"},
      {block_case("[[program.step]]\ndirichlet_scale = [1.0]\n"), "solve",
       "program.step[0].dirichlet_scale"},
      {block_case("[[force]]\nboundary = \"top\"\nforce = [1.0, 0.0, 0.0]\n"), "solve",
       "force[0].force[0]"},
      {block_case("[[force]]\nat = [0.05, 0.05]\ntolerance = 0.0\nforce = [1.0, 0.0, 0.0]\n"),
       "solve", "force[0].at"},
  };
  for (const Bad& b : cases) {
    const fs::path c = write_case(dir, b.text);
    const RunResult r = run(b.command + " " + c.string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(b.expected), std::string::npos)
        << b.expected << " not in: " << r.output;
  }
  const fs::path c = write_case(
      dir, std::string(block_case(""))
               .replace(block_case("").find("normal_force = 1.0e4"), 20, "normal_force = -1.0"));
  const RunResult r = run("experiment " + c.string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("experiment.normal_force"), std::string::npos) << r.output;
}

// drive = "force": the block floats, pulled by a top shear ramped until no equilibrium exists;
// a polygon law (the floating solver's equilibria reach its capacity closely, docs/experiments.md).
std::string force_drive_case(const std::string& drive_keys) {
  std::string text = block_case("");
  text.replace(text.find("[experiment]"), std::string::npos,
               "[experiment]\n" + drive_keys + "normal_force = 1.0e4\nangles_degrees = [0]\nramp_steps = 4\n");
  const std::string disc = "kind = \"disc_exact\"\nmu = 0.3";
  text.replace(text.find(disc), disc.size(), "kind = \"isotropic\"\nmu = 0.3\nn = 8");
  return text;
}

TEST(CliExperiment, ForceDriveReportsTheOnsetAtTheCapacity) {
  const fs::path dir = fresh_directory("experiment_force");
  const fs::path c =
      write_case(dir, force_drive_case("drive = \"force\"\nmax_force_ratio = 0.4\nonset_tolerance = 1e-4\n"));
  const RunResult r = run("experiment " + c.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("no static equilibrium beyond Q"), std::string::npos) << r.output;
  const auto json = frictopt::io::parse_json(read_text(dir / "out" / "summary.json"));
  EXPECT_EQ(json.at("drive").as_string(), "force");
  for (const auto& a : json.at("angles").as_array()) {
    ASSERT_TRUE(a.at("gross_sliding").as_bool());
    // θ = 0 on the 8-gon (vertices at ±22.5°): μ(0°) = 0.3·cos 22.5°, an edge midpoint.
    const double capacity = 0.3 * std::cos(std::numbers::pi / 8.0) * 1e4;
    EXPECT_LE(a.at("onset_force").as_number(), capacity * (1.0 + 1e-12));
    EXPECT_NEAR(a.at("onset_force").as_number(), capacity, 1e-3 * capacity);
  }
}

TEST(CliExperiment, BadForceDriveExitsTwoNamingTheField) {
  const fs::path dir = fresh_directory("experiment_force_bad");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"drive = \"torque\"\nmax_force_ratio = 0.4\n", "experiment.drive"},
      {"drive = \"force\"\n", "max_force_ratio"},
      {"drive = \"force\"\nmax_force_ratio = -1.0\n", "experiment.max_force_ratio"},
      {"drive = \"force\"\nmax_force_ratio = 0.4\nonset_tolerance = 0.5\n", "experiment.onset_tolerance"},
  };
  for (const auto& [keys, expected] : cases) {
    const fs::path c = write_case(dir, force_drive_case(keys));
    const RunResult r = run("experiment " + c.string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << " not in: " << r.output;
  }
}

// A floating block: no [[dirichlet]]; pressed by a top pressure and pulled by a top shear.
std::string floating_case(double shear) {
  return R"(
[geometry]
dim = 3
a = 0.1
b = 0.1
height = 0.05
[mesh]
cells = [4, 4, 2]
[material]
young = 7.0e10
poisson = 0.33
[[load]]
face = "top"
traction = [)" +
         std::to_string(shear) + R"(, 0.0, -1.0e6]
[design]
control_points = [2, 2]
initial = [0.0, 0.0, 0.0, 0.0]
upper_bound = 1.0e-3
[contact.friction]
kind = "disc_exact"
mu = 0.3
)";
}

TEST(CliFloating, InsideTheCapacitySolvesBeyondItExitsThreeWithTheExcess) {
  const fs::path dir = fresh_directory("floating");
  const RunResult inside = run("solve " + write_case(dir, floating_case(1.5e5)).string() + " -o " +
                               (dir / "a").string());
  ASSERT_EQ(inside.exit_code, 0) << inside.output;
  const auto json = frictopt::io::parse_json(read_text(dir / "a" / "summary.json"));
  EXPECT_EQ(json.at("contact").at("floating").at("status").as_string(), "converged");
  EXPECT_NEAR(json.at("contact").at("total_normal_force").as_number(), 1e4, 1e-4);
  const RunResult beyond = run("solve " + write_case(dir, floating_case(4.5e5)).string() + " -o " +
                               (dir / "b").string());
  EXPECT_EQ(beyond.exit_code, 3) << beyond.output;
  EXPECT_NE(
      beyond.output.find("exceeds the friction capacity μ(θ)·P = 0.3 × 10000 N = 3000 N by 50 %"),
      std::string::npos)
      << beyond.output;
}

}  // namespace
