// SPDX-License-Identifier: MIT
// Linear tetrahedra through the command line (docs/meshes.md, "Tetrahedra and triangles"): the
// shipped punch-tet on a coarse grid passes check-gradient (every ξ_k matches central
// differences), optimizes to a certified stationary point, certifies, and export-shape writes a
// .msh of tetrahedra that frictopt reads back as P1 cells; the die of Gmsh kept in tetrahedra
// solves at a size where its subdivided hexahedra are refused (an inverted corner); the part
// from CAD (cases3d/step-pad) is what its pad-cad.geo makes, and solves from its STEP file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/cli_runner.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::fresh_directory;
using frictopt::testing::read_text;
using frictopt::testing::replace_key;
using frictopt::testing::RunResult;
using frictopt::testing::write_text;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

const fs::path kSource = FRICTOPT_SOURCE_DIR;

TEST(CliTetrahedra, CoarsePunchChecksOptimizesCertifiesAndExports) {
  const fs::path dir = fresh_directory("cli_tetrahedra_punch");
  fs::create_directories(dir);
  std::string text = read_text(kSource / "cases3d/punch-tet/case.toml");
  text = replace_key(text, "cells", "[8, 8, 4]");
  text = replace_key(text, "every", "100");
  write_text(dir / "case.toml", text);

  const RunResult check = run("check-gradient " + (dir / "case.toml").string());
  ASSERT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("0 MISMATCH"), std::string::npos) << check.output;

  const fs::path out = dir / "run";
  const RunResult optimize = run("optimize " + (dir / "case.toml").string() + " -o " + out.string());
  ASSERT_EQ(optimize.exit_code, 0) << optimize.output;
  const auto summary = frictopt::io::parse_json(read_text(out / "summary.json"));
  EXPECT_EQ(summary.at("status").as_string(), "converged");
  EXPECT_LT(summary.at("final_cost").as_number(), 0.1 * summary.at("initial_cost").as_number());

  const RunResult certify = run("certify " + out.string());
  EXPECT_EQ(certify.exit_code, 0) << certify.output;
  EXPECT_NE(certify.output.find("stationary at the stated tolerance"), std::string::npos) << certify.output;

  const RunResult exported = run("export-shape " + out.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const fs::path msh = out / "punch-tet_optimized.msh";
  ASSERT_TRUE(fs::exists(msh)) << exported.output;
  const frictopt::mesh::Mesh back =
      frictopt::mesh::GmshMesh(msh, {.family = frictopt::mesh::ElementFamily::kSimplex}).take_mesh();
  EXPECT_EQ(back.element_kind(), frictopt::mesh::ElementKind::kTet4);
  EXPECT_EQ(back.num_elements(), 8 * 8 * 4 * 6);
  EXPECT_EQ(back.boundary("bottom").facets.cols(), 3);
  EXPECT_TRUE(fs::exists(out / "punch-tet_optimized.stl"));
  EXPECT_TRUE(fs::exists(out / "punch-tet_design.step"));
}

TEST(CliTetrahedra, DieKeptInTetrahedraSolvesWhereItsSubdividedHexahedraAreRefused) {
  const fs::path dir = fresh_directory("cli_tetrahedra_die");
  fs::create_directories(dir);
  std::string text = read_text(kSource / "cases3d/gmsh-die-tet/case.toml");
  text = replace_key(text, "file", "\"" + (kSource / "cases3d/gmsh-die/die.geo").string() + "\"");
  text = replace_key(text, "size", "0.007");
  write_text(dir / "tet.toml", text);
  const RunResult tet = run("solve " + (dir / "tet.toml").string() + " -o " + (dir / "tet").string());
  ASSERT_EQ(tet.exit_code, 0) << tet.output;
  EXPECT_NE(tet.output.find("(tet4, smallest scaled Jacobian"), std::string::npos) << tet.output;
  const auto summary = frictopt::io::parse_json(read_text(dir / "tet" / "summary.json"));
  EXPECT_EQ(summary.at("element").as_string(), "tet4");
  EXPECT_GT(summary.at("min_scaled_jacobian").as_number(), 0.05);

  write_text(dir / "hex.toml", replace_key(text, "element", "\"hex8\""));
  const RunResult hex = run("solve " + (dir / "hex.toml").string() + " -o " + (dir / "hex").string());
  EXPECT_EQ(hex.exit_code, 2) << hex.output;
  EXPECT_NE(hex.output.find("is inverted for the mesh as read"), std::string::npos) << hex.output;
}

// The STEP file without its FILE_NAME line (the time of writing): the rest is the geometry.
std::string step_without_timestamp(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream out;
  for (std::string line; std::getline(in, line);)
    if (line.find("FILE_NAME(") == std::string::npos) out << line << '\n';
  return out.str();
}

TEST(CliTetrahedra, StepPartIsReproducibleFromItsGeoAndSolves) {
  const fs::path dir = fresh_directory("cli_tetrahedra_step");
  fs::create_directories(dir);
  const fs::path made = dir / "pad.step";
  const std::string command = "gmsh -0 " + (kSource / "cases3d/step-pad/pad-cad.geo").string() + " -o " + made.string() +
                              " -format step > " + (dir / "gmsh.log").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(dir / "gmsh.log");
  EXPECT_EQ(step_without_timestamp(made), step_without_timestamp(kSource / "cases3d/step-pad/pad.step"))
      << "cases3d/step-pad/pad.step is not what pad-cad.geo makes: run cases3d/step-pad/make_step.sh";
  const RunResult solve =
      run("solve " + (kSource / "cases3d/step-pad/case.toml").string() + " -o " + (dir / "solve").string());
  ASSERT_EQ(solve.exit_code, 0) << solve.output;
  EXPECT_NE(solve.output.find("(tet4, smallest scaled Jacobian"), std::string::npos) << solve.output;
  const auto summary = frictopt::io::parse_json(read_text(dir / "solve" / "summary.json"));
  EXPECT_GT(summary.at("contact").at("num_contact_nodes").as_number(), 100);
}

}  // namespace
