// SPDX-License-Identifier: MIT
// The optimized shape out (docs/meshes.md, "The optimized shape out"): the STEP surface read back
// by OpenCASCADE matches the Bézier patch to 1e-9 of its size, and the .msh / STL files hold the
// body they were given.
#include "frictopt/mesh/cad_export.hpp"

#include <gmsh.h>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <sys/wait.h>
#include <unistd.h>

#include "common/invalid_input.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/mesh/structured_mesh.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::mesh {
namespace {

namespace fs = std::filesystem;
using testing::invalid_input_message;

fs::path write_temp(const std::string& name, const std::string& bytes) {
  const fs::path dir = fs::temp_directory_path() / "frictopt_cad_export_test";
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

// A wavy 4 × 3 patch over [0.01, 0.05] × [−0.02, 0.01] m in a tilted frame, heights of tens of µm:
// a part at its real size, in metres.
BezierGeometry wavy_surface() {
  BezierGeometry g;
  g.m1 = 4;
  g.m2 = 3;
  g.points.resize(12, 3);
  const Eigen::Vector3d n = Eigen::Vector3d(0.1, -0.2, 1.0).normalized();
  const Eigen::Vector3d e1 = Eigen::Vector3d(1.0, 0.0, -0.1).cross(n).cross(n).normalized() * -1.0;
  const Eigen::Vector3d e2 = n.cross(e1);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      g.points.row(i + 4 * j) = (e1 * (0.01 + 0.04 * i / 3.0) + e2 * (-0.02 + 0.03 * j / 2.0) +
                                 n * (0.003 + 2e-5 * std::sin(1.0 + i * 1.7 + j * 0.9)))
                                    .transpose();
  return g;
}

// Imports a STEP file with OpenCASCADE in metres and returns the largest distance between the
// entity of dimension `dim` and the Bézier geometry on a 21 × 21 grid of parameters. In a child
// process, as frictopt runs every Gmsh session: a second Gmsh session in one process imports
// the next STEP file in millimetres (Geometry.OCCTargetUnit is not applied again).
double step_read_back_distance_here(const fs::path& file, const BezierGeometry& g, int dim);
double step_read_back_distance(const fs::path& file, const BezierGeometry& g, int dim) {
  int fds[2];
  if (::pipe(fds) != 0) return INFINITY;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    const double d = step_read_back_distance_here(file, g, dim);
    const bool ok = ::testing::Test::HasFailure() == false;
    const double message[2] = {d, ok ? 1.0 : 0.0};
    [[maybe_unused]] const auto written = ::write(fds[1], message, sizeof message);
    ::_exit(0);
  }
  ::close(fds[1]);
  double message[2] = {INFINITY, 0.0};
  const auto got = ::read(fds[0], message, sizeof message);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_EQ(got, static_cast<ssize_t>(sizeof message)) << "the read-back child ended without an answer";
  EXPECT_EQ(message[1], 1.0) << "the read-back child found one entity of dimension " << dim << " and its vertices";
  return message[0];
}
double step_read_back_distance_here(const fs::path& file, const BezierGeometry& g, int dim) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setString("Geometry.OCCTargetUnit", "M");
  gmsh::vectorpair shapes;
  gmsh::model::occ::importShapes(file.string(), shapes);
  gmsh::model::occ::synchronize();
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, dim);
  EXPECT_EQ(entities.size(), 1u) << "one " << (dim == 2 ? "surface" : "curve") << " in " << file;
  gmsh::vectorpair points;
  gmsh::model::getEntities(points, 0);
  EXPECT_EQ(points.size(), dim == 2 ? 4u : 2u) << "only the shape's own vertices, no loose control points";
  double worst = INFINITY;
  if (entities.size() == 1) {
    const int tag = entities[0].second;
    std::vector<double> lo, hi;
    gmsh::model::getParametrizationBounds(dim, tag, lo, hi);
    worst = 0.0;
    const int n = 20;
    for (int a = 0; a <= n; ++a)
      for (int b = 0; b <= (dim == 2 ? n : 0); ++b) {
        const double u = double(a) / n, v = double(b) / n;
        std::vector<double> param{lo[0] + u * (hi[0] - lo[0])};
        if (dim == 2) param.push_back(lo[1] + v * (hi[1] - lo[1]));
        std::vector<double> xyz;
        gmsh::model::getValue(dim, tag, param, xyz);
        const Eigen::Vector3d s = evaluate(g, u, v);
        worst = std::max(worst, (Eigen::Vector3d(xyz[0], xyz[1], xyz[2]) - s).norm());
      }
  }
  gmsh::finalize();
  return worst;
}

TEST(BezierEvaluation, ReproducesTheCornersAndLinearPrecision) {
  BezierGeometry g;
  g.m1 = 5;
  g.m2 = 4;
  g.points.resize(20, 3);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) g.points.row(i + 5 * j) << 2.0 * i / 4.0, 3.0 * j / 3.0, 1.0 + 0.5 * i / 4.0 - j / 3.0;
  const Eigen::Vector3d s = evaluate(g, 0.3, 0.7);
  EXPECT_NEAR(s.x(), 0.6, 1e-15);
  EXPECT_NEAR(s.y(), 2.1, 1e-15);
  EXPECT_NEAR(s.z(), 1.0 + 0.15 - 0.7, 1e-15);
  EXPECT_EQ(evaluate(g, 1.0, 1.0), Eigen::Vector3d(g.points.row(19).transpose()));
}

TEST(BezierStep, SurfaceReadBackMatchesTheDesignTo1e9OfItsSize) {
  const BezierGeometry g = wavy_surface();
  const std::string bytes = bezier_step(g, "wavy");
  ASSERT_NE(bytes.find("ISO-10303-21"), std::string::npos);
  EXPECT_NE(bytes.find("B_SPLINE_SURFACE"), std::string::npos) << "an exact spline surface, not a mesh";
  EXPECT_NE(bytes.find("MILLI"), std::string::npos) << "lengths in millimetres";
  const double size = std::hypot(0.04, 0.03);
  EXPECT_LE(step_read_back_distance(write_temp("wavy.step", bytes), g, 2), 1e-9 * size);
}

TEST(BezierStep, CurveReadBackMatchesTheDesign) {
  BezierGeometry g;
  g.m1 = 6;
  g.m2 = 1;
  g.points = Eigen::MatrixXd::Zero(6, 3);
  for (int i = 0; i < 6; ++i) g.points.row(i) << 0.02 * i / 5.0, 1e-5 * std::cos(2.0 * i), 0.0;
  const std::string bytes = bezier_step(g, "curve");
  EXPECT_LE(step_read_back_distance(write_temp("curve.step", bytes), g, 1), 1e-9 * 0.02);
}

TEST(BezierStep, RefusesNonFiniteAndMisshapenControlNets) {
  BezierGeometry g = wavy_surface();
  g.points(3, 1) = NAN;
  EXPECT_NE(invalid_input_message([&] { (void)bezier_step(g, "bad"); }).find("not finite"), std::string::npos);
  g = wavy_surface();
  g.m1 = 5;
  EXPECT_NE(invalid_input_message([&] { (void)bezier_step(g, "bad"); }).find("control points"), std::string::npos);
}

Mesh box(int dim) {
  const shape::BezierShape shape =
      dim == 3 ? shape::BezierShape::surface(0.02, 0.01, 3, 3) : shape::BezierShape::curve(0.02, 3);
  GridResolution r;
  r.cells = {3, dim == 3 ? 2 : 0, 2};
  return StructuredMesh(shape, 0.005, r).take_mesh();
}

TEST(ExteriorFacets, AreTheBoxFacesOrientedOutward) {
  for (int dim : {2, 3}) {
    const Mesh mesh = box(dim);
    const Connectivity f = exterior_facets(mesh);
    const int expected = dim == 3 ? 2 * (3 * 2 + 3 * 2 + 2 * 2) : 2 * (3 + 2);
    ASSERT_EQ(f.rows(), expected) << dim << "D";
    const Eigen::MatrixXd& X = mesh.reference_positions();
    const Eigen::VectorXd centre = X.colwise().mean().transpose();
    for (Eigen::Index r = 0; r < f.rows(); ++r) {
      Eigen::VectorXd normal, middle = Eigen::VectorXd::Zero(dim);
      for (Eigen::Index k = 0; k < f.cols(); ++k) middle += X.row(f(r, k)).transpose() / double(f.cols());
      if (dim == 3) {
        const Eigen::Vector3d d1 = X.row(f(r, 2)) - X.row(f(r, 0)), d2 = X.row(f(r, 3)) - X.row(f(r, 1));
        normal = d1.cross(d2);
      } else {
        const Eigen::Vector2d t = X.row(f(r, 1)) - X.row(f(r, 0));
        normal = Eigen::Vector2d(t.y(), -t.x());
      }
      EXPECT_GT(normal.dot(middle - centre), 0.0) << dim << "D facet " << r << " points inward";
    }
  }
}

TEST(MeshFile, GmshFileReadsBackAsTheSameBody) {
  for (int dim : {2, 3}) {
    const Mesh mesh = box(dim);
    // A design-like motion so that positions differ from the reference.
    Eigen::MatrixXd X = mesh.reference_positions();
    X.col(dim - 1).array() += 1e-4 * X.col(0).array().sin();
    const fs::path file =
        write_temp(dim == 3 ? "box3.msh" : "box2.msh", mesh_file(mesh, X, MeshFileFormat::kGmsh, "body"));
    const Mesh back = GmshMesh(file).mesh();
    ASSERT_EQ(back.num_nodes(), mesh.num_nodes());
    ASSERT_EQ(back.num_elements(), mesh.num_elements());
    EXPECT_EQ(back.boundary_names(), mesh.boundary_names());
    EXPECT_LE((back.reference_positions() - X).cwiseAbs().maxCoeff(), 1e-15);  // Gmsh writes 17 digits
    for (const std::string& name : mesh.boundary_names())
      EXPECT_EQ(back.boundary(name).nodes, mesh.boundary(name).nodes) << name;
    EXPECT_NEAR(back.volume(back.reference_positions()), mesh.volume(X), 1e-15);
  }
}

TEST(MeshFile, StlEnclosesTheBodysVolume) {
  const Mesh mesh = box(3);
  Eigen::MatrixXd X = mesh.reference_positions();
  X.col(2).array() += 2e-4 * (X.col(0).array() * 300.0).sin() * (1.0 - X.col(2).array() / 0.005);
  const std::string bytes = mesh_file(mesh, X, MeshFileFormat::kStl, "body");
  ASSERT_GE(bytes.size(), 84u);
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  const Connectivity f = exterior_facets(mesh);
  ASSERT_EQ(count, 2 * f.rows());
  ASSERT_EQ(bytes.size(), 84u + 50u * count);
  // Divergence theorem: V = Σ (p0 · (p1 × p2)) / 6 over outward triangles.
  double volume = 0.0;
  for (std::uint32_t t = 0; t < count; ++t) {
    float v[9];
    std::memcpy(v, bytes.data() + 84 + 50 * t + 12, sizeof v);
    const Eigen::Vector3d p0(v[0], v[1], v[2]), p1(v[3], v[4], v[5]), p2(v[6], v[7], v[8]);
    volume += p0.dot(p1.cross(p2)) / 6.0;
  }
  // The bilinear faces are split into two planar triangles: the volumes differ by that, and by single precision.
  EXPECT_NEAR(volume, mesh.volume(X), 1e-3 * mesh.volume(X));
}

TEST(MeshFile, RefusesAnStlOfA2DBodyAndPositionsOfAnotherSize) {
  const Mesh mesh = box(2);
  EXPECT_NE(invalid_input_message([&] {
              (void)mesh_file(mesh, mesh.reference_positions(), MeshFileFormat::kStl, "b");
            }).find("2D"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([&] {
              (void)mesh_file(mesh, Eigen::MatrixXd::Zero(3, 2), MeshFileFormat::kGmsh, "b");
            }).find("expected"),
            std::string::npos);
}

}  // namespace
}  // namespace frictopt::mesh
