// SPDX-License-Identifier: MIT
// End-to-end checks of `frictopt certify RUN_DIR`: on a fresh (3-iteration) optimize run it
// prints the certificate and writes certificate.json whose numbers are consistent with each
// other and with the printed report; a run directory without final_design.json is an input
// error (exit code 2) naming the file.
#include <gtest/gtest.h>

#include "common/cli_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;

using frictopt::testing::RunResult;
using frictopt::testing::read_text;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

/// `x` printed as the report prints it (fmt's "{:.Ne}" and printf's "%.Ne" agree).
std::string scientific(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", digits, x);
  return buf;
}

// An imported body names its mesh relative to the case file; the run directory's copy of the
// case lives elsewhere, so certify RUN_DIR and --resume must still find the mesh (the copy names
// it absolutely) and the resume must see the same problem (regression: exit 2, "no such file").
TEST(CliCertify, FindsTheMeshOfAnImportedBodyNamedRelativeToTheCase) {
  const fs::path dir = frictopt::testing::fresh_directory("cli_certify_imported");
  fs::create_directories(dir);
  const fs::path case_path = dir / "case.toml";
  fs::copy_file(FRICTOPT_SOURCE_DIR "/cases2d/gmsh-body/body.geo", dir / "body.geo");
  std::ofstream(case_path) << std::regex_replace(read_text(FRICTOPT_SOURCE_DIR "/cases2d/gmsh-body/case.toml"),
                                                 std::regex(R"(max_iterations = \d+)"), "max_iterations = 2",
                                                 std::regex_constants::format_first_only);
  const fs::path run_dir = dir / "run";
  const RunResult optimize = run("optimize " + case_path.string() + " -o " + run_dir.string());
  ASSERT_EQ(optimize.exit_code, 0) << optimize.output;
  EXPECT_NE(read_text(run_dir / "case.toml").find((dir / "body.geo").lexically_normal().string()), std::string::npos);
  const RunResult certify = run("certify " + run_dir.string());
  EXPECT_EQ(certify.exit_code, 0) << certify.output;
  const RunResult resumed = run("optimize " + case_path.string() + " -o " + run_dir.string() + " --resume");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
}

TEST(CliCertify, WritesCertificateJsonForAFreshRun) {
  const fs::path dir = frictopt::testing::fresh_directory("cli_certify_run");
  fs::create_directories(dir);
  // certify accepts any run with a final design: a copy of the case capped at 3 iterations.
  const fs::path case_path = dir / "case.toml";
  std::ofstream(case_path) << read_text(FRICTOPT_SOURCE_DIR "/cases2d/thesis-body/case.toml")
                           << "\n[optimization]\nmax_iterations = 3\n";
  const RunResult optimize = run("optimize " + case_path.string() + " -o " + (dir / "run").string());
  ASSERT_EQ(optimize.exit_code, 0) << optimize.output;
  const fs::path run_dir = dir / "run";
  const RunResult r = run("certify " + run_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("(MF1')"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(run_dir / "certificate.json"));
  const auto json = frictopt::io::parse_json(read_text(run_dir / "certificate.json"));
  EXPECT_EQ(json.at("command").as_string(), "certify");
  EXPECT_EQ(json.at("status").as_string(), "converged");
  EXPECT_GE(json.at("cardinality_L").as_number(), 1.0);
  // The scale is max_i |ξ_i| over the pieces written; the relative distance is distance/scale
  // (doubles are written with max_digits10, so the quotient is reproduced exactly).
  const double scale = json.at("scale_max_xi_norm").as_number();
  double largest = 0.0;
  for (const auto& piece : json.at("pieces").as_array()) {
    double squares = 0.0;
    for (const auto& x : piece.at("xi").as_array()) squares += x.as_number() * x.as_number();
    largest = std::max(largest, std::sqrt(squares));
  }
  ASSERT_GT(scale, 0.0);
  EXPECT_NEAR(largest, scale, 1e-13 * scale);
  const auto& clarke = json.at("clarke");
  const double distance = clarke.at("distance").as_number();
  const double relative = clarke.at("relative_distance").as_number();
  EXPECT_DOUBLE_EQ(relative, distance / scale);
  EXPECT_LE(relative, 1.0 + 1e-12);
  EXPECT_EQ(clarke.at("stationary").as_bool(), distance <= clarke.at("stationary_tolerance_relative").as_number() * scale);
  // The printed report shows the same numbers to its printed precision.
  std::smatch printed;
  ASSERT_TRUE(std::regex_search(r.output, printed,
                                std::regex(R"(Clarke distance [^\n]*= (\S+) \(relative (\S+)\))")))
      << r.output;
  EXPECT_EQ(printed[1].str(), scientific(distance, 6)) << r.output;
  EXPECT_EQ(printed[2].str(), scientific(relative, 3)) << r.output;
  EXPECT_NE(r.output.find("scale max_i |xi_i| = " + scientific(scale, 6)), std::string::npos) << r.output;
  EXPECT_TRUE(json.at("mf1").at("computed").as_bool());
  EXPECT_GE(json.at("mf1").at("rank").as_integer(), 1);
  EXPECT_EQ(json.at("pieces").as_array().size(),
            static_cast<std::size_t>(json.at("sampled").as_bool() ? 4096 : json.at("cardinality_L").as_number()));
  EXPECT_FALSE(json.contains("goldstein")) << "no sampled certificate unless asked for";

  // The sampled (Goldstein) certificate: 6 designs within 1e-6 m; its generators contain those at
  // x, so its distance cannot exceed the exact one (up to the QP's accuracy).
  const RunResult g = run("certify " + run_dir.string() + " --sample-radius 1e-6 --samples 6");
  ASSERT_EQ(g.exit_code, 0) << g.output;
  EXPECT_NE(g.output.find("sampled certificate: 6 of 6 sampled designs within 1.000e-06"), std::string::npos) << g.output;
  const auto sampled = frictopt::io::parse_json(read_text(run_dir / "certificate.json")).at("goldstein");
  EXPECT_EQ(sampled.at("evaluated").as_integer(), 6);
  EXPECT_GT(sampled.at("largest_step").as_number(), 0.0);
  EXPECT_LE(sampled.at("largest_step").as_number(), 1e-6 * (1.0 + 1e-12));
  EXPECT_LE(sampled.at("distance").as_number(), distance * (1.0 + 1e-6) + 1e-12 * scale);
  const RunResult bad = run("certify " + run_dir.string() + " --sample-radius -1");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
}

TEST(CliCertify, MissingFinalDesignIsAnInputErrorNamingTheFile) {
  const fs::path dir = frictopt::testing::fresh_directory("cli_certify_missing");
  fs::create_directories(dir);
  fs::copy_file(FRICTOPT_SOURCE_DIR "/cases2d/thesis-body/case.toml", dir / "case.toml");
  const RunResult r = run("certify " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("final_design.json"), std::string::npos) << r.output;
  const RunResult none = run("certify " + (dir / "no-such-run").string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("no-such-run"), std::string::npos) << none.output;
}

}  // namespace
