// SPDX-License-Identifier: MIT
// `frictopt export-shape RUN_DIR` (docs/meshes.md, "The optimized shape out"): the design patch
// as STEP — read back by OpenCASCADE it passes through every designed patch node of the exported
// .msh to 1e-9 of the patch's size — the body as .msh (read back by frictopt's own reader: the
// designed positions and the boundary sets) and STL; a curved patch gets a note instead of a
// STEP surface; a directory that is not a run, a design of the wrong size and a file frictopt did
// not write at an output name are refused (exit 2) and nothing is overwritten.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <regex>
#include <string>

#include "common/cli_runner.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::fresh_directory;
using frictopt::testing::read_text;
using frictopt::testing::RunResult;
using frictopt::testing::write_text;
RunResult run(const std::string& arguments) { return frictopt::testing::run_frictopt(arguments); }

std::string fmt_double(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

// A run directory made by hand, as `optimize` leaves it for certify: the case copy (mesh files
// named absolutely) and final_design.json with a wavy design of amplitude `amplitude` around α⁰.
fs::path hand_made_run(const std::string& tag, std::string case_text, double amplitude) {
  const fs::path dir = fresh_directory(tag);
  fs::create_directories(dir / "run");
  write_text(dir / "run" / "case.toml", case_text);
  const frictopt::io::CaseDescription d = frictopt::io::load_case(dir / "run" / "case.toml");
  frictopt::study::ElasticBody body(d.body);
  Eigen::VectorXd x = body.initial_design();
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += amplitude * std::sin(1.0 + 2.3 * double(i));
  std::string json = "{\"alpha\": [";
  for (Eigen::Index i = 0; i < x.size(); ++i) json += (i ? ", " : "") + fmt_double(x(i));
  write_text(dir / "run" / "final_design.json", json + "]}\n");
  return dir / "run";
}

// Every node of boundary set `patch` of the exported .msh is the STEP file's one surface (3D) or
// curve (2D), read with OpenCASCADE in metres, at the node's chart parameters: the patch moves
// along x_dim (the standard frame of these cases), so (u, v) are the node's in-plane coordinates
// over the patch's bounding rectangle. Returns the largest distance [m]. (Evaluating at the
// parameters rather than projecting: OpenCASCADE's point projection on a curve stops at ~1e-8.)
double step_distance_to_patch(const fs::path& step, const fs::path& msh, const std::string& patch) {
  const frictopt::mesh::Mesh body = frictopt::mesh::GmshMesh(msh).mesh();
  const int dim = body.dim();
  const Eigen::MatrixXd& X = body.reference_positions();
  const std::vector<int>& nodes = body.boundary(patch).nodes;
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(dim - 1, INFINITY), hi = -lo;
  for (int node : nodes)
    for (int c = 0; c + 1 < dim; ++c) {
      lo(c) = std::min(lo(c), X(node, c));
      hi(c) = std::max(hi(c), X(node, c));
    }
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setString("Geometry.OCCTargetUnit", "M");
  gmsh::vectorpair shapes;
  gmsh::model::occ::importShapes(step.string(), shapes);
  gmsh::model::occ::synchronize();
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, dim - 1);
  double worst = INFINITY;
  if (entities.size() == 1) {
    worst = 0.0;
    const int tag = entities[0].second;
    std::vector<double> pmin, pmax;
    gmsh::model::getParametrizationBounds(dim - 1, tag, pmin, pmax);
    for (int node : nodes) {
      std::vector<double> parameters;
      for (int c = 0; c + 1 < dim; ++c)
        parameters.push_back(pmin[c] + (X(node, c) - lo(c)) / (hi(c) - lo(c)) * (pmax[c] - pmin[c]));
      std::vector<double> xyz;
      gmsh::model::getValue(dim - 1, tag, parameters, xyz);
      const double z = dim == 3 ? X(node, 2) : 0.0;
      worst = std::max(worst, std::hypot(xyz[0] - X(node, 0), xyz[1] - X(node, 1), xyz[2] - z));
    }
  }
  gmsh::finalize();
  return worst;
}

// The exported .msh holds the designed body: positions X(α) of the run's design, the same sets.
void expect_msh_is_the_designed_body(const fs::path& run_dir, const fs::path& msh) {
  const frictopt::io::CaseDescription d = frictopt::io::load_case(run_dir / "case.toml");
  frictopt::study::ElasticBody body(d.body);
  const Eigen::VectorXd x = frictopt::io::read_design_file(run_dir / "final_design.json", body.num_design_variables());
  const Eigen::MatrixXd X = body.mesh().positions(x.head(d.body.shape.num_controls()));
  const frictopt::mesh::Mesh back = frictopt::mesh::GmshMesh(msh).mesh();
  ASSERT_EQ(back.num_nodes(), body.mesh().num_nodes());
  EXPECT_LE((back.reference_positions() - X).cwiseAbs().maxCoeff(), 1e-15 * (1.0 + X.cwiseAbs().maxCoeff()));
  EXPECT_EQ(back.boundary_names(), body.mesh().boundary_names());
}

std::string case_text(const std::string& relative) { return read_text(fs::path(FRICTOPT_SOURCE_DIR) / relative); }

TEST(CliExportShape, StructuredPunchGivesStepMshAndStl) {
  // A real run, two iterations of the 3D punch: the design has moved from α⁰.
  const fs::path dir = fresh_directory("cli_export_punch");
  fs::create_directories(dir);
  // The demo case (3D punch, anisotropic friction, 4 × 4 net), two iterations.
  const std::string text =
      frictopt::testing::replace_key(case_text("cases3d/punch-anisotropic/case.toml"), "max_iterations", "2");
  write_text(dir / "case.toml", text);
  const RunResult opt = run("optimize " + (dir / "case.toml").string() + " -o " + (dir / "run").string());
  ASSERT_TRUE(opt.exit_code == 0 || opt.exit_code == 3 || opt.exit_code == 6) << opt.output;
  const RunResult r = run("export-shape " + (dir / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string name = frictopt::io::load_case(dir / "run" / "case.toml").output.name;
  const fs::path step = dir / "run" / (name + "_design.step"), msh = dir / "run" / (name + "_optimized.msh");
  ASSERT_TRUE(fs::exists(step)) << r.output;
  ASSERT_TRUE(fs::exists(dir / "run" / (name + "_optimized.stl"))) << r.output;
  EXPECT_NE(r.output.find("Bézier surface of 4×4"), std::string::npos) << r.output;
  expect_msh_is_the_designed_body(dir / "run", msh);
  const frictopt::io::CaseDescription d = frictopt::io::load_case(dir / "run" / "case.toml");
  const auto [a, b] = d.body.shape.extents();
  EXPECT_LE(step_distance_to_patch(step, msh, "bottom"), 1e-9 * std::hypot(a, b));
  // Again: the files are ours and are replaced.
  const RunResult again = run("export-shape " + (dir / "run").string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

TEST(CliExportShape, TwoDimensionalBodyGivesACurveAndNoStl) {
  const fs::path run_dir = hand_made_run("cli_export_2d", case_text("cases2d/thesis-body/case.toml"), 0.01);
  const RunResult r = run("export-shape " + run_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Bézier curve of 15×1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no STL"), std::string::npos) << r.output;
  const std::string name = frictopt::io::load_case(run_dir / "case.toml").output.name;
  const fs::path msh = run_dir / (name + "_optimized.msh");
  expect_msh_is_the_designed_body(run_dir, msh);
  EXPECT_LE(step_distance_to_patch(run_dir / (name + "_design.step"), msh, "bottom"), 1e-9 * 2.0);
  EXPECT_FALSE(fs::exists(run_dir / (name + "_optimized.stl")));
}

TEST(CliExportShape, ImportedGmshPunchMatchesItsPatch) {
  std::string text = case_text("cases3d/gmsh-punch/case.toml");
  text = std::regex_replace(text, std::regex(R"(file = "punch.geo")"),
                            "file = \"" + std::string(FRICTOPT_SOURCE_DIR) + "/cases3d/gmsh-punch/punch.geo\"");
  const fs::path run_dir = hand_made_run("cli_export_gmsh", text, 2e-4);
  const RunResult r = run("export-shape " + run_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string name = frictopt::io::load_case(run_dir / "case.toml").output.name;
  const fs::path msh = run_dir / (name + "_optimized.msh");
  expect_msh_is_the_designed_body(run_dir, msh);
  const frictopt::io::CaseDescription d = frictopt::io::load_case(run_dir / "case.toml");
  const auto [a, b] = d.body.shape.extents();
  EXPECT_LE(step_distance_to_patch(run_dir / (name + "_design.step"), msh, "Bottom"), 1e-9 * std::hypot(a, b));
}

TEST(CliExportShape, ACurvedPatchGetsANoteAndTheMeshOnly) {
  const fs::path dir = fresh_directory("cli_export_curved");
  fs::create_directories(dir);
  // A 2D arch: the lower half of a ring (outer radius 0.5 m) whose outer arc is the patch.
  write_text(dir / "arch.geo", R"(SetFactory("OpenCASCADE");
Disk(1) = {0, 0.5, 0, 0.5};
Disk(2) = {0, 0.5, 0, 0.3};
Rectangle(3) = {-1, 0.5, 0, 2, 1};
BooleanDifference(4) = {Surface{1}; Delete;}{Surface{2, 3}; Delete;};
Mesh.RecombineAll = 1;
Mesh.MeshSizeMax = 0.05;
e = 1e-6;
top[] = Curve In BoundingBox{-1, 0.5 - e, -e, 1, 0.5 + e, e};
inner[] = Curve In BoundingBox{-0.3 - e, 0.2 - e, -e, 0.3 + e, 0.5 + e, e};
outer[] = Curve{:};
outer[] -= top[];
outer[] -= inner[];
Physical Surface("Body") = {4};
Physical Curve("Top") = {top[]};
Physical Curve("Outer") = {outer[]};
Physical Curve("Inner") = {inner[]};
)");
  std::string text = case_text("cases2d/gmsh-body/case.toml");
  text = std::regex_replace(text, std::regex(R"(file = "body.geo")"), "file = \"" + (dir / "arch.geo").string() + "\"");
  text = std::regex_replace(text, std::regex(R"(contact = "Bottom")"), "contact = \"Outer\"");
  text = std::regex_replace(text, std::regex(R"(boundary = "Left")"), "boundary = \"Inner\"");
  text = std::regex_replace(text, std::regex(R"(size = 0.07)"), "size = 0.05");
  text = frictopt::testing::replace_key(text, "initial", "0.0");
  fs::create_directories(dir / "run");
  const fs::path run_dir = hand_made_run("cli_export_curved_run", text, 1e-3);
  const RunResult r = run("export-shape " + run_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("not plane"), std::string::npos) << r.output;
  const std::string name = frictopt::io::load_case(run_dir / "case.toml").output.name;
  EXPECT_FALSE(fs::exists(run_dir / (name + "_design.step")));
  expect_msh_is_the_designed_body(run_dir, run_dir / (name + "_optimized.msh"));
}

TEST(CliExportShape, RefusesWhatIsNotARunAndKeepsForeignFiles) {
  const fs::path dir = fresh_directory("cli_export_refusals");
  fs::create_directories(dir / "empty");
  const RunResult none = run("export-shape " + (dir / "empty").string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  // A design of the wrong size.
  const fs::path run_dir = hand_made_run("cli_export_refusals_run", case_text("cases2d/thesis-body/case.toml"), 0.01);
  write_text(dir / "short.json", "{\"alpha\": [0.1, 0.2]}\n");
  const RunResult wrong = run("export-shape " + run_dir.string() + " --design " + (dir / "short.json").string());
  EXPECT_EQ(wrong.exit_code, 2) << wrong.output;
  EXPECT_NE(wrong.output.find("short.json"), std::string::npos) << wrong.output;
  // A symbolic link at an output name is not ours: refused, its target untouched.
  const std::string name = frictopt::io::load_case(run_dir / "case.toml").output.name;
  write_text(dir / "precious.txt", "keep me");
  fs::create_symlink(dir / "precious.txt", run_dir / (name + "_optimized.msh"));
  const RunResult link = run("export-shape " + run_dir.string());
  EXPECT_EQ(link.exit_code, 2) << link.output;
  EXPECT_EQ(read_text(dir / "precious.txt"), "keep me");
  EXPECT_TRUE(fs::is_symlink(run_dir / (name + "_optimized.msh")));
}

}  // namespace
