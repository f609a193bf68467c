// SPDX-License-Identifier: MIT
#include "frictopt/mesh/cad_export.hpp"

#include <fmt/format.h>
#include <gmsh.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

#include "frictopt/core/error.hpp"
#include "gmsh_session.hpp"
#include "mesh_child_process.hpp"

namespace frictopt::mesh {
namespace fs = std::filesystem;
namespace {

// Gmsh element type numbers (Gmsh's reference manual, "MSH file format").
constexpr int kGmshLine2 = 1;
constexpr int kGmshTriangle3 = 2;
constexpr int kGmshQuad4 = 3;
constexpr int kGmshTetra4 = 4;
constexpr int kGmshHexa8 = 5;

// STEP's customary length unit; OpenCASCADE's writer labels the model's numbers as millimetres.
constexpr double kMillimetresPerMetre = 1000.0;

// A private directory for Gmsh's output (Gmsh writes only to files; the format follows the
// extension). Made and removed inside the child, so nothing is left when the child is killed
// by its time limit but an empty folder under the system's temporary directory.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    std::string pattern = (fs::temp_directory_path() / "frictopt-export-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw InvalidInput(fmt::format("cannot make a temporary directory under {}", fs::temp_directory_path().string()));
    path_ = pattern;
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  ~ScratchDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("Gmsh wrote no {}", file.filename().string()));
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes the current Gmsh model to a scratch file of the given extension and returns its bytes.
std::string write_model(const std::string& what, const std::string& extension) {
  ScratchDirectory scratch;
  const fs::path file = scratch.path() / ("export" + extension);
  detail::gmsh_call(file, "write the " + what, [&] { gmsh::write(file.string()); });
  return read_bytes(file);
}

detail::ChildLimits export_limits() {
  detail::ChildLimits limits;
  limits.seconds = 600.0;
  return limits;
}

// The local faces of Q1 cells in VTK/Gmsh node order, each listed so that the right-hand rule
// gives the outward normal of a positively oriented cell.
constexpr std::array<std::array<int, 4>, 6> kHexFaces{{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
constexpr std::array<std::array<int, 2>, 4> kQuadEdges{{{0, 1}, {1, 2}, {2, 3}, {3, 0}}};
// The same for P1 cells.
constexpr std::array<std::array<int, 3>, 4> kTetFaces{{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}};
constexpr std::array<std::array<int, 2>, 3> kTriangleEdges{{{0, 1}, {1, 2}, {2, 0}}};

// Gmsh's element type of a mesh's cells and of its boundary facets.
int gmsh_cell_type(ElementKind kind) {
  switch (kind) {
    case ElementKind::kQuad4: return kGmshQuad4;
    case ElementKind::kHex8: return kGmshHexa8;
    case ElementKind::kTri3: return kGmshTriangle3;
    case ElementKind::kTet4: return kGmshTetra4;
  }
  return kGmshHexa8;
}
int gmsh_facet_type(ElementKind kind) {
  switch (nodes_per_facet(kind)) {
    case 2: return kGmshLine2;
    case 3: return kGmshTriangle3;
    default: return kGmshQuad4;
  }
}

}  // namespace

Eigen::Vector3d evaluate(const BezierGeometry& g, double u, double v) {
  // de Casteljau along u for every row j, then along v (Farin, "Curves and Surfaces for CAGD", §4).
  const auto casteljau = [](std::vector<Eigen::Vector3d> p, double t) {
    for (std::size_t r = 1; r < p.size(); ++r)
      for (std::size_t i = 0; i + r < p.size(); ++i) p[i] = (1.0 - t) * p[i] + t * p[i + 1];
    return p.front();
  };
  std::vector<Eigen::Vector3d> rows;
  for (int j = 0; j < g.m2; ++j) {
    std::vector<Eigen::Vector3d> row;
    for (int i = 0; i < g.m1; ++i) row.push_back(g.points.row(i + g.m1 * j).transpose());
    rows.push_back(casteljau(row, u));
  }
  return casteljau(rows, v);
}

std::string bezier_step(const BezierGeometry& geometry, const std::string& name) {
  if (geometry.m1 < 2 || geometry.m2 < 1 || geometry.points.rows() != geometry.m1 * geometry.m2 ||
      geometry.points.cols() != 3)
    throw InvalidInput(fmt::format("Bézier geometry '{}': {}×{} control points given as a {}×{} array; expected "
                                   "m1 ≥ 2 and (m1·m2)×3",
                                   name, geometry.m1, geometry.m2, geometry.points.rows(), geometry.points.cols()));
  if (!geometry.points.allFinite())
    throw InvalidInput(fmt::format("Bézier geometry '{}': a control point is not finite", name));
  return detail::run_in_child("STEP export of " + name, export_limits(), [&]() -> std::string {
    detail::GmshSession session;
    const fs::path label = name + ".step";
    std::vector<int> points;
    detail::gmsh_call(label, "build the Bézier geometry", [&] {
      gmsh::model::add(name);
      for (Eigen::Index k = 0; k < geometry.points.rows(); ++k)
        points.push_back(gmsh::model::occ::addPoint(kMillimetresPerMetre * geometry.points(k, 0),
                                                    kMillimetresPerMetre * geometry.points(k, 1),
                                                    kMillimetresPerMetre * geometry.points(k, 2)));
      std::vector<std::pair<int, int>> loose;  // control points that are not the shape's vertices
      if (geometry.m2 == 1) {
        gmsh::model::occ::addBezier(points);  // its end points become the curve's vertices
        for (std::size_t k = 1; k + 1 < points.size(); ++k) loose.emplace_back(0, points[k]);
      } else {
        gmsh::model::occ::addBezierSurface(points, geometry.m1);  // a face with vertices of its own
        for (int p : points) loose.emplace_back(0, p);
      }
      // The control points are not part of the shape: a CAD system would show them as loose vertices.
      if (!loose.empty()) gmsh::model::occ::remove(loose);
      gmsh::model::occ::synchronize();
    });
    return write_model("STEP file", ".step");
  });
}

Connectivity exterior_facets(const Mesh& mesh) {
  const Connectivity& cells = mesh.elements();
  const ElementKind kind = mesh.element_kind();
  const int per_facet = nodes_per_facet(kind);
  // A facet is interior when two cells share it: count each facet by its sorted node list.
  std::map<std::array<int, 4>, int> count;
  std::vector<std::array<int, 4>> oriented;
  for (Eigen::Index e = 0; e < cells.rows(); ++e) {
    const auto add = [&](const int* local, int n) {
      std::array<int, 4> f{-1, -1, -1, -1};
      for (int k = 0; k < n; ++k) f[k] = cells(e, local[k]);
      std::array<int, 4> key = f;
      std::sort(key.begin(), key.begin() + n);
      ++count[key];
      oriented.push_back(f);
    };
    switch (kind) {
      case ElementKind::kHex8: for (const auto& face : kHexFaces) add(face.data(), 4); break;
      case ElementKind::kQuad4: for (const auto& edge : kQuadEdges) add(edge.data(), 2); break;
      case ElementKind::kTet4: for (const auto& face : kTetFaces) add(face.data(), 3); break;
      case ElementKind::kTri3: for (const auto& edge : kTriangleEdges) add(edge.data(), 2); break;
    }
  }
  std::vector<std::array<int, 4>> exterior;
  for (const auto& f : oriented) {
    std::array<int, 4> key = f;
    std::sort(key.begin(), key.begin() + per_facet);
    if (count[key] == 1) exterior.push_back(f);
  }
  Connectivity out(static_cast<Eigen::Index>(exterior.size()), per_facet);
  for (std::size_t r = 0; r < exterior.size(); ++r)
    for (int k = 0; k < per_facet; ++k) out(static_cast<Eigen::Index>(r), k) = exterior[r][k];
  return out;
}

std::string mesh_file(const Mesh& mesh, const Eigen::Ref<const Eigen::MatrixXd>& X, MeshFileFormat format,
                      const std::string& volume_name) {
  const int dim = mesh.dim();
  if (X.rows() != mesh.num_nodes() || X.cols() != dim)
    throw InvalidInput(fmt::format("mesh export: positions of {}×{}; expected {}×{}", X.rows(), X.cols(),
                                   mesh.num_nodes(), dim));
  if (!X.allFinite()) throw InvalidInput("mesh export: a node position is not finite");
  if (format == MeshFileFormat::kStl && dim != 3)
    throw InvalidInput("mesh export: an STL file holds a surface; a 2D body has none (write the .msh)");
  // Copied before the fork: the child reads them, the parent's Mesh is not touched.
  std::vector<double> coordinates(static_cast<std::size_t>(3 * mesh.num_nodes()), 0.0);
  std::vector<std::size_t> node_tags(static_cast<std::size_t>(mesh.num_nodes()));
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    node_tags[i] = static_cast<std::size_t>(i) + 1;
    for (int c = 0; c < dim; ++c) coordinates[3 * i + c] = X(i, c);
  }
  const auto gmsh_nodes = [](const Connectivity& c) {
    std::vector<std::size_t> nodes;
    nodes.reserve(static_cast<std::size_t>(c.size()));
    for (Eigen::Index r = 0; r < c.rows(); ++r)
      for (Eigen::Index k = 0; k < c.cols(); ++k) nodes.push_back(static_cast<std::size_t>(c(r, k)) + 1);
    return nodes;
  };
  return detail::run_in_child("mesh export", export_limits(), [&]() -> std::string {
    detail::GmshSession session;
    const fs::path label = volume_name + (format == MeshFileFormat::kStl ? ".stl" : ".msh");
    std::size_t next_element = 1;
    const auto element_tags = [&](std::size_t n) {
      std::vector<std::size_t> tags(n);
      for (auto& t : tags) t = next_element++;
      return tags;
    };
    detail::gmsh_call(label, "build the mesh", [&] {
      gmsh::model::add(volume_name);
      if (format == MeshFileFormat::kStl) {
        // Only the exterior surface, as triangles (STL has no other facet): each outward
        // quadrilateral (a, b, c, d) as (a, b, c) and (a, c, d), a triangle as it is.
        const Connectivity facets = exterior_facets(mesh);
        std::vector<std::size_t> triangles;
        const std::vector<int> split = facets.cols() == 3 ? std::vector<int>{0, 1, 2} : std::vector<int>{0, 1, 2, 0, 2, 3};
        for (Eigen::Index r = 0; r < facets.rows(); ++r)
          for (int k : split) triangles.push_back(static_cast<std::size_t>(facets(r, k)) + 1);
        const int surface = gmsh::model::addDiscreteEntity(2);
        gmsh::model::mesh::addNodes(2, surface, node_tags, coordinates);
        gmsh::model::mesh::addElementsByType(surface, kGmshTriangle3, element_tags(triangles.size() / 3), triangles);
        gmsh::option::setNumber("Mesh.Binary", 1);
        return;
      }
      const int body = gmsh::model::addDiscreteEntity(dim);
      gmsh::model::mesh::addNodes(dim, body, node_tags, coordinates);
      const std::vector<std::size_t> cell_nodes = gmsh_nodes(mesh.elements());
      gmsh::model::mesh::addElementsByType(body, gmsh_cell_type(mesh.element_kind()),
                                           element_tags(static_cast<std::size_t>(mesh.num_elements())), cell_nodes);
      gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, {body}), volume_name);
      for (const std::string& name : mesh.boundary_names()) {
        const BoundarySet& set = mesh.boundary(name);
        const int entity = gmsh::model::addDiscreteEntity(dim - 1);
        gmsh::model::mesh::addElementsByType(entity, gmsh_facet_type(mesh.element_kind()),
                                             element_tags(static_cast<std::size_t>(set.facets.rows())),
                                             gmsh_nodes(set.facets));
        gmsh::model::setPhysicalName(dim - 1, gmsh::model::addPhysicalGroup(dim - 1, {entity}), name);
      }
      gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
      gmsh::option::setNumber("Mesh.Binary", 0);
    });
    return write_model(format == MeshFileFormat::kStl ? "STL file" : "mesh file",
                       format == MeshFileFormat::kStl ? ".stl" : ".msh");
  });
}

}  // namespace frictopt::mesh
