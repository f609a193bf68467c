// SPDX-License-Identifier: MIT
// Loading plates through the command line (docs/case-format.md, "[[plate]]"): `solve` and
// `optimize` on the example cases3d/punch-plate report the plate's force and travel, and the
// contact carries the prescribed force at the initial and the final design; `check-gradient`
// matches its differences; a floating body with a free rotation is refused (exit 2).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/cli_runner.hpp"
#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;

using frictopt::testing::fresh_directory;
using frictopt::testing::replace_key;
using frictopt::testing::RunResult;
using frictopt::testing::write_text;

RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The example with a few iterations (the test's time).
std::string coarse_example() {
  std::string text = read(FRICTOPT_SOURCE_DIR "/cases3d/punch-plate/case.toml");
  text = replace_key(text, "max_iterations", "6");
  return text;
}

double press_force(const frictopt::io::JsonValue& plates) { return -plates.as_array()[0].at("force").as_array()[2].as_number(); }

TEST(CliPlate, SolveAndOptimizeCarryThePrescribedForce) {
  const fs::path dir = fresh_directory("plate");
  fs::create_directories(dir);
  write_text(dir / "case.toml", coarse_example());
  const RunResult solved = run("solve " + (dir / "case.toml").string() + " -o " + (dir / "solve").string());
  ASSERT_EQ(solved.exit_code, 0) << solved.output;
  EXPECT_NE(solved.output.find("plate \"top\": displacement"), std::string::npos) << solved.output;
  const auto summary = frictopt::io::parse_json(read(dir / "solve" / "summary.json"));
  const auto& plates = summary.at("plates");
  const double F = -plates.as_array()[0].at("prescribed_force").as_array()[2].as_number();
  ASSERT_GT(F, 0.0);
  EXPECT_NEAR(press_force(plates), F, 1e-8 * F);
  EXPECT_NEAR(summary.at("contact").at("total_normal_force").as_number(), F, 1e-8 * F);
  EXPECT_EQ(plates.as_array()[0].at("displacement").as_array()[1].as_number(), 0.0);  // held
  EXPECT_EQ(plates.as_array()[0].at("displacement").as_array()[0].as_number(), 0.0);  // held
  EXPECT_LT(plates.as_array()[0].at("displacement").as_array()[2].as_number(), 0.0);  // pressed down

  const RunResult optimized = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string());
  ASSERT_TRUE(optimized.exit_code == 0 || optimized.exit_code == 6) << optimized.output;  // limit or attention
  const auto run_summary = frictopt::io::parse_json(read(dir / "run" / "summary.json"));
  std::printf("initial P = %.12e N, final P = %.12e N (prescribed %.6e N); plate travel %.6e -> %.6e m\n",
              run_summary.at("initial_load").at("total_normal_force").as_number(),
              run_summary.at("final_load").at("total_normal_force").as_number(), F,
              run_summary.at("initial_plates").as_array()[0].at("displacement").as_array()[2].as_number(),
              run_summary.at("final_plates").as_array()[0].at("displacement").as_array()[2].as_number());
  EXPECT_NEAR(run_summary.at("initial_load").at("total_normal_force").as_number(), F, 1e-8 * F);
  EXPECT_NEAR(run_summary.at("final_load").at("total_normal_force").as_number(), F, 1e-8 * F);
  EXPECT_NEAR(press_force(run_summary.at("final_plates")), F, 1e-8 * F);
  EXPECT_NE(run_summary.at("final_cost").as_number(), run_summary.at("initial_cost").as_number());  // it did move
}

TEST(CliPlate, CheckGradientMatchesItsDifferences) {
  const fs::path dir = fresh_directory("plate_gradient");
  fs::create_directories(dir);
  write_text(dir / "case.toml", coarse_example());
  const RunResult r = run("check-gradient " + (dir / "case.toml").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex(R"(largest error relative to max\|ξ\|: ([0-9.eE+-]+))"))) << r.output;
  std::printf("check-gradient with a plate: largest error %s of max|xi|\n", m[1].str().c_str());
  EXPECT_LE(std::stod(m[1].str()), 1e-4) << r.output;
}

TEST(CliPlate, FloatingBodyWithAFreeRotationIsRefusedForSensitivities) {
  // The example without its plate, pressed by a traction: no Dirichlet condition, 6 free modes.
  std::string text = coarse_example();
  const std::size_t at = text.find("\n[[plate]]") + 1;  // the table, not the header's mention
  const std::size_t end = text.find("\n[design]") + 1;
  ASSERT_NE(at, 0u);
  text.replace(at, end - at, "[[load]]\nface = \"top\"\ntraction = [0.0, 0.0, -3.0e7]\n\n");
  const fs::path dir = fresh_directory("plate_rotation");
  fs::create_directories(dir);
  write_text(dir / "case.toml", text);
  const RunResult solved = run("solve " + (dir / "case.toml").string() + " -o " + (dir / "solve").string());
  EXPECT_EQ(solved.exit_code, 0) << solved.output;  // the state is solved
  const RunResult r = run("check-gradient " + (dir / "case.toml").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("include a rotation"), std::string::npos) << r.output;
  const RunResult o = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("include a rotation"), std::string::npos) << o.output;
}

}  // namespace
