// SPDX-License-Identifier: MIT
// End-to-end checks of `frictopt solve`: it writes a .vtu that VTK reads back with the
// displacement and stress arrays, a summary.json, and rejects bad cases with a clear message.
#include <gtest/gtest.h>

#include "common/cli_runner.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frictopt/io/json.hpp"
#include "frictopt/io/vtu_reader.hpp"

namespace {

namespace fs = std::filesystem;

using frictopt::testing::RunResult;
using frictopt::testing::fresh_directory;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }


TEST(CliSolve, Writes3dVtuWithDisplacementAndStressArrays) {
  const fs::path out = fresh_directory("solve3d");
  const RunResult r = run("solve " FRICTOPT_SOURCE_DIR "/tests/cli/data/small3d.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto vtu = frictopt::io::read_vtu_arrays(out / "small3d.vtu");
  EXPECT_EQ(vtu.num_points, 7 * 6 * 5);
  EXPECT_EQ(vtu.num_cells, 6 * 5 * 4);
  ASSERT_NE(vtu.point_array("displacement"), nullptr);
  EXPECT_EQ(vtu.point_array("displacement")->num_components, 3);
  ASSERT_NE(vtu.point_array("stress"), nullptr);
  EXPECT_EQ(vtu.point_array("stress")->num_components, 9);
  ASSERT_NE(vtu.point_array("von_mises"), nullptr);
  ASSERT_NE(vtu.cell_array("von_mises"), nullptr);
  ASSERT_NE(vtu.point_array("boundary_tag"), nullptr);
  // The top is pressed down: the vertical displacement of the top far from the clamp is < 0.
  EXPECT_LT(vtu.point_array("displacement")->values.col(2).minCoeff(), 0.0);
  const auto summary = frictopt::io::parse_json([&] {
    std::ifstream in(out / "summary.json");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }());
  EXPECT_EQ(summary.at("status").as_string(), "converged");
  EXPECT_LT(summary.at("relative_residual").as_number(), 1e-10);
}

// README "Reproducibility": a run is bit-reproducible only for a fixed BLAS thread count, so its
// summary records the policy it was made under (the Python summaries carry the same key).
TEST(CliSolve, SummaryRecordsTheBlasThreadPolicy) {
  const fs::path out = fresh_directory("solve_blas");
  ::setenv("FRICTOPT_BLAS_THREADS", "1", 1);
  const RunResult r = run("solve " FRICTOPT_SOURCE_DIR "/tests/cli/data/small3d.toml -o " + out.string());
  ::unsetenv("FRICTOPT_BLAS_THREADS");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  const auto summary = frictopt::io::parse_json(text.str());
  ASSERT_TRUE(summary.contains("blas_threads")) << text.str();
  EXPECT_NE(summary.at("blas_threads").as_string().find("FRICTOPT_BLAS_THREADS = 1"), std::string::npos)
      << summary.at("blas_threads").as_string();
  // ... and the BLAS it was made with (the implementation and the library dgemm_ binds to).
  ASSERT_TRUE(summary.contains("blas")) << text.str();
  EXPECT_EQ(summary.at("blas").as_string().rfind("OpenBLAS", 0), 0U) << summary.at("blas").as_string();
}

// The shipped binary calls OpenBLAS, not the ATLAS that Debian's libceres.so needs as well
// (docs/benchmarks.md, "Which BLAS"): `frictopt --version` names the BLAS dgemm_ binds to.
TEST(CliVersion, NamesOpenBlasAsTheBlasTheBinaryCalls) {
  const RunResult r = run("--version");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("frictopt 0."), std::string::npos) << r.output;
  const auto blas = r.output.find("BLAS: OpenBLAS");
  ASSERT_NE(blas, std::string::npos) << r.output;
  const auto from = r.output.find("(dgemm_ from ", blas);
  ASSERT_NE(from, std::string::npos) << r.output;
  const std::string library = r.output.substr(from, r.output.find(')', from) - from);
  EXPECT_NE(library.find("openblas"), std::string::npos) << library;
  EXPECT_EQ(library.find("atlas"), std::string::npos) << library;
  EXPECT_EQ(library.find("f77blas"), std::string::npos) << library;
}

TEST(CliSolve, Writes2dVtuForTheThesisBody) {
  const fs::path out = fresh_directory("solve2d");
  const RunResult r = run("solve " FRICTOPT_SOURCE_DIR "/tests/cli/data/small2d.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto vtu = frictopt::io::read_vtu_arrays(out / "small2d.vtu");
  EXPECT_EQ(vtu.num_points, 30 * 15);
  ASSERT_NE(vtu.point_array("displacement"), nullptr);
}

TEST(CliSolve, RejectsAnInitialDesignAboveTheUpperBoundNamingTheField) {
  // A control height above C0 (and here above the top, which would invert elements) is
  // caught by the case validation before any mesh is built; the mesh's own inverted-element
  // check is tested in tests/mesh.
  const RunResult r = run("solve " FRICTOPT_SOURCE_DIR "/tests/cli/data/inverted3d.toml -o " +
                          fresh_directory("inverted").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("design.initial[3]"), std::string::npos) << r.output;
}

TEST(CliCheckGradient, CentralDifferencesMatchTheAdjointOnTheThesisExample) {
  // study::check_gradient through the command: the thesis' example 5.2.1 at its flat start has
  // strict index sets, so every quotient matches ξ (last measured 3.8e-8 of max|ξ|).
  const RunResult r = run("check-gradient " FRICTOPT_SOURCE_DIR "/cases2d/ex521-target-pressure/case.toml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string key = "largest error relative to max|ξ|: ";
  const std::size_t at = r.output.find(key);
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_LT(std::stod(r.output.substr(at + key.size())), 1e-6) << r.output;
}

TEST(CliSolve, RejectsAMissingCaseFile) {
  const RunResult r = run("solve /nonexistent/case.toml");
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("case.toml"), std::string::npos) << r.output;
}

}  // namespace
