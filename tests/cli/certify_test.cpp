// SPDX-License-Identifier: MIT
// End-to-end checks of `frictopt certify RUN_DIR`: on a fresh optimize run it prints the
// certificate and writes certificate.json; a run directory without final_design.json is an
// input error (exit code 2) naming the file.
#include <gtest/gtest.h>

#include "common/cli_runner.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;

using frictopt::testing::RunResult;
using frictopt::testing::read_text;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }


TEST(CliCertify, WritesCertificateJsonForAFreshRun) {
  const fs::path dir = frictopt::testing::fresh_directory("cli_certify_run");
  const RunResult optimize = run("optimize " FRICTOPT_SOURCE_DIR "/cases2d/thesis-body/case.toml -o " + dir.string());
  ASSERT_EQ(optimize.exit_code, 0) << optimize.output;
  const RunResult r = run("certify " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Clarke distance"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(MF1')"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(dir / "certificate.json"));
  const auto json = frictopt::io::parse_json(read_text(dir / "certificate.json"));
  EXPECT_EQ(json.at("command").as_string(), "certify");
  EXPECT_EQ(json.at("status").as_string(), "converged");
  EXPECT_GE(json.at("cardinality_L").as_number(), 1.0);
  EXPECT_GE(json.at("clarke").at("distance").as_number(), 0.0);
  EXPECT_GE(json.at("clarke").at("relative_distance").as_number(), 0.0);
  EXPECT_LE(json.at("clarke").at("relative_distance").as_number(), 1.0 + 1e-12);
  EXPECT_TRUE(json.at("mf1").at("computed").as_bool());
  EXPECT_GE(json.at("mf1").at("rank").as_integer(), 1);
  EXPECT_EQ(json.at("pieces").as_array().size(),
            static_cast<std::size_t>(json.at("sampled").as_bool() ? 4096 : json.at("cardinality_L").as_number()));
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
