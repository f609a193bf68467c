// SPDX-License-Identifier: MIT
#include "frictopt/io/shape_export.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/mesh/design_extension.hpp"

namespace frictopt::io {
namespace {

// A patch whose reference nodes leave the plane n·X = t₀ by more than this share of its size is
// curved: moving it along one normal gives no Bézier surface in space.
constexpr double kPlaneTolerance = 1e-9;

}  // namespace

DesignSurface design_surface(const study::ElasticBody& body, const Eigen::Ref<const Eigen::VectorXd>& x,
                             const Eigen::Ref<const Eigen::MatrixXd>& X) {
  const study::BodyDefinition& d = body.definition();
  const shape::BezierShape& shape = d.shape;
  const mesh::Mesh& mesh = body.mesh();
  const int dim = shape.dim();
  if (x.size() < shape.num_controls())
    throw InvalidInput(
        fmt::format("design of {} values; the shape has {} control points", x.size(), shape.num_controls()));
  const Eigen::VectorXd alpha = x.head(shape.num_controls());  // without the orientation's s
  // The chart: as summary.json's design_chart (io/summary_json.cpp) — the imported patch's frame
  // and bounding rectangle, or the box's own axes with the Bézier surface as its bottom.
  mesh::PlaneFrame frame = mesh::PlaneFrame::standard(dim);
  Eigen::VectorXd origin = Eigen::VectorXd::Zero(dim - 1);
  std::string patch = d.contact_surface;
  if (d.imported_mesh) {
    const mesh::DesignMotion& motion = d.imported_mesh->motion;
    if (motion.frame.normal.size() == dim) frame = motion.frame;
    origin = mesh::patch_chart(*d.imported_mesh->reference, motion.patch, frame).origin;
    patch = motion.patch;
  }
  const auto [m1, m2_net] = shape.control_net();
  const int m2 = dim == 3 ? m2_net : 1;
  const auto [a, b] = shape.extents();
  DesignSurface out;
  out.size = dim == 3 ? std::hypot(a, b) : a;

  const std::vector<int>& nodes = mesh.boundary(patch).nodes;
  const Eigen::MatrixXd& reference = mesh.reference_positions();
  // t₀ and the flatness of the reference patch along n.
  double lo = INFINITY, hi = -INFINITY;
  for (int i : nodes) {
    const double h = frame.normal.dot(reference.row(i).transpose());
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  const double t0 = 0.5 * (lo + hi);
  if (hi - lo > kPlaneTolerance * out.size) {
    out.note = fmt::format("the design patch '{}' is not plane in the reference (it spans {:.3e} m along its normal, "
                           "{:.1e} of its size): its motion along one normal is no Bézier surface in space, so no "
                           "STEP surface is written; the optimized body is in the .msh/.stl",
                           patch, hi - lo, (hi - lo) / out.size);
    return out;
  }
  // P_ij = T (c + (a i/(m1−1), b j/(m2−1))) + (t₀ + α_ij) n, embedded in 3-space.
  mesh::BezierGeometry g;
  g.m1 = m1;
  g.m2 = m2;
  g.points = Eigen::MatrixXd::Zero(m1 * m2, 3);
  for (int j = 0; j < m2; ++j)
    for (int i = 0; i < m1; ++i) {
      Eigen::VectorXd p = (t0 + alpha(i + m1 * j)) * frame.normal;
      p += frame.tangents.col(0) * (origin(0) + a * i / (m1 - 1));
      if (dim == 3) p += frame.tangents.col(1) * (origin(1) + b * j / (m2 - 1));
      g.points.row(i + m1 * j).head(dim) = p.transpose();
    }
  // The surface against the designed mesh at every patch node.
  for (int i : nodes) {
    const Eigen::VectorXd r = reference.row(i).transpose();
    const double u = (frame.tangents.col(0).dot(r) - origin(0)) / a;
    const double v = dim == 3 ? (frame.tangents.col(1).dot(r) - origin(1)) / b : 0.0;
    const Eigen::Vector3d s = mesh::evaluate(g, u, v);
    out.max_node_deviation = std::max(out.max_node_deviation, (s.head(dim) - X.row(i).transpose()).norm());
  }
  out.geometry = std::move(g);
  return out;
}

ShapeExport export_shape(const std::filesystem::path& run_dir, const std::filesystem::path& design_file) {
  RunDirectory run(run_dir, RunOpening::kExisting);
  const std::filesystem::path case_path = run.store_case();
  const CaseDescription description = load_case(case_path);
  study::ElasticBody body(description.body);
  run.check_run_fingerprint(fingerprint_of(description, body));  // case.toml edited after the run: refused
  const std::filesystem::path design_path = design_file.empty() ? run.file(RunDirectory::kFinalDesign) : design_file;
  const Eigen::VectorXd x = read_design_file(design_path, body.num_design_variables());
  const Eigen::VectorXd alpha = x.head(body.definition().shape.num_controls());
  const mesh::Mesh& mesh = body.mesh();
  const Eigen::MatrixXd X = mesh.positions(alpha);
  mesh.check_quality(X, design_path.string());  // an inverted cell is no body to export

  ShapeExport out;
  const std::string& name = description.output.name;
  const auto write = [&](const std::string& file, const std::string& bytes) {
    run.write_text_file(file, bytes);
    out.files.push_back(run.file(file));
  };
  out.surface = design_surface(body, x, X);
  if (out.surface.geometry) {
    // The surface is built from α and the chart only; a deviation from the mesh beyond round-off
    // would mean the chart is not the one the mesh moved with: refuse rather than write a wrong part.
    if (out.surface.max_node_deviation > 1e-9 * out.surface.size)
      throw NumericalFailure(fmt::format("{}: the Bézier surface of the design misses the designed mesh by {:.3e} m "
                                         "({:.1e} of the patch's size {:.3e} m); no STEP file written",
                                         design_path.string(), out.surface.max_node_deviation,
                                         out.surface.max_node_deviation / out.surface.size, out.surface.size));
    write(name + "_design.step", mesh::bezier_step(*out.surface.geometry, name + "_design"));
  } else {
    out.notes.push_back(out.surface.note);
  }
  write(name + "_optimized.msh", mesh::mesh_file(mesh, X, mesh::MeshFileFormat::kGmsh, name));
  if (mesh.dim() == 3)
    write(name + "_optimized.stl", mesh::mesh_file(mesh, X, mesh::MeshFileFormat::kStl, name));
  else
    out.notes.push_back("a 2D body has no STL (a surface format): its outline is in the .msh");
  return out;
}

}  // namespace frictopt::io
