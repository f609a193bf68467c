// SPDX-License-Identifier: MIT
#include "frictopt/mesh/gmsh_mesh.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <system_error>
#include <unordered_map>

#include <stdlib.h>  // mkstemps
#include <unistd.h>  // write, close

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/elements.hpp"

namespace frictopt::mesh {
namespace {

// The finest .geo meshing accepted: extent/size cells along the body's largest extent.
constexpr double kMaxCellsPerExtent3d = 200.0;
constexpr double kMaxCellsPerExtent2d = 2000.0;

// Gmsh element type numbers (Gmsh's reference manual, "MSH file format").
constexpr int kGmshLine2 = 1;
constexpr int kGmshTriangle3 = 2;
constexpr int kGmshQuad4 = 3;
constexpr int kGmshTetra4 = 4;
constexpr int kGmshHexa8 = 5;

std::string gmsh_type_name(int type) {
  switch (type) {
    case kGmshLine2: return "2-node lines";
    case kGmshTriangle3: return "3-node triangles";
    case kGmshQuad4: return "4-node quadrilaterals";
    case kGmshTetra4: return "4-node tetrahedra";
    case kGmshHexa8: return "8-node hexahedra";
    default: break;
  }
  std::string name;
  int dim = 0, order = 0, num_nodes = 0, num_primary = 0;
  std::vector<double> local;
  try {
    gmsh::model::mesh::getElementProperties(type, name, dim, order, num_nodes, local, num_primary);
  } catch (...) {
    return fmt::format("Gmsh element type {}", type);
  }
  return fmt::format("{} (Gmsh element type {})", name, type);
}

// Gmsh keeps one global model and is not thread-safe: every use holds this lock from
// initialize() to finalize(), and the guard finalizes on every path (also when we throw).
std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

class GmshSession {
 public:
  GmshSession() : lock_(gmsh_mutex()) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    // Never write to stdout (our outputs and the CLI's report own it); errors are collected
    // from the logger into our messages.
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  ~GmshSession() { gmsh::finalize(); }

 private:
  std::lock_guard<std::mutex> lock_;
};

// Runs a Gmsh call; a failure (Gmsh throws objects of unspecified type) becomes InvalidInput
// with Gmsh's last error message.
template <class F>
void gmsh_call(const std::filesystem::path& file, std::string_view what, F&& f) {
  try {
    f();
  } catch (const InvalidInput&) {
    throw;
  } catch (...) {
    std::string error;
    try {
      gmsh::logger::getLastError(error);
    } catch (...) {
    }
    throw InvalidInput(fmt::format("{}: Gmsh could not {}: {}", file.string(), what,
                                   error.empty() ? "no message from Gmsh" : error));
  }
}

// Gmsh 4.8's .geo parser keeps the rest of a statement it failed on and fails on it at the next
// parse in the process, even after finalize() (reproduced: a good file then reports "line 0:
// syntax error (;)"). Parsing a file holding only a comment consumes that rest. The file is
// created exclusively (mkstemps) and removed again.
void reset_geo_parser() {
  std::string path = (std::filesystem::temp_directory_path() / "frictopt-gmsh-reset-XXXXXX.geo").string();
  const int fd = ::mkstemps(path.data(), 4);
  if (fd < 0) return;  // no reset possible: only a later parse in this process is affected
  const char comment[] = "// frictopt: resets Gmsh's parser after a syntax error\n";
  const bool written = ::write(fd, comment, sizeof(comment) - 1) == static_cast<ssize_t>(sizeof(comment) - 1);
  ::close(fd);
  if (written) {
    try {
      gmsh::merge(path);
    } catch (...) {  // expected: the rest of the failed statement is reported here
    }
  }
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

struct ElementBlock {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags;
  std::vector<std::vector<std::size_t>> nodes;
};

// All elements of dimension `dim` on the given entities (all entities of that dimension when
// `entities` is empty), grouped by type.
std::map<int, std::pair<std::vector<std::size_t>, std::vector<std::size_t>>> elements_of(
    int dim, const std::vector<int>& entities) {
  std::map<int, std::pair<std::vector<std::size_t>, std::vector<std::size_t>>> by_type;
  const auto add = [&](int tag) {
    ElementBlock b;
    gmsh::model::mesh::getElements(b.types, b.tags, b.nodes, dim, tag);
    for (std::size_t k = 0; k < b.types.size(); ++k) {
      auto& [tags, nodes] = by_type[b.types[k]];
      tags.insert(tags.end(), b.tags[k].begin(), b.tags[k].end());
      nodes.insert(nodes.end(), b.nodes[k].begin(), b.nodes[k].end());
    }
  };
  if (entities.empty()) {
    add(-1);
  } else {
    for (int tag : entities) add(tag);
  }
  return by_type;
}

std::string physical_name(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? std::to_string(tag) : name;
}

struct ReadResult {
  Mesh mesh;
  bool subdivided = false;
  std::vector<std::size_t> element_tags;
};

ReadResult read(const std::filesystem::path& file, const GmshMeshOptions& options) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InvalidInput(fmt::format("{}: mesh file not found (or not a regular file); expected a Gmsh .msh or .geo file",
                                   name));
  const std::string extension = file.extension().string();
  const bool is_geo = extension == ".geo";
  if (!is_geo && extension != ".msh")
    throw InvalidInput(fmt::format("{}: mesh file with extension '{}'; expected .msh (Gmsh mesh, format 4.1 or 2.2) "
                                   "or .geo (Gmsh geometry, meshed at load time)",
                                   name, extension));
  const bool has_size = !std::isnan(options.size);
  if (has_size && !(options.size > 0 && std::isfinite(options.size)))
    throw InvalidInput(fmt::format("{}: mesh size {}; expected a number > 0 [m]", name, options.size));
  if (has_size && !is_geo)
    throw InvalidInput(fmt::format("{}: a mesh size is given for a .msh file, which is read as it is; expected a size "
                                   "only for a .geo file",
                                   name));

  GmshSession session;
  try {
    gmsh_call(file, "read the file", [&] { gmsh::open(name); });
  } catch (const InvalidInput&) {
    if (is_geo) reset_geo_parser();
    throw;
  }
  int dim = gmsh::model::getDimension();
  if (is_geo) {
    if (dim < 2)
      throw InvalidInput(fmt::format("{}: the geometry has no {}; expected a 2D surface or a 3D volume", name,
                                     dim < 0 ? "entities" : "surface or volume"));
    if (has_size) {
      // Bounded before meshing, so that a mistyped size (1e-9 m) is an error and not hours of
      // Gmsh and an exhausted memory: (extent/size)^dim cells stay near the case files' limit
      // of 2,000,000 unknowns (docs/case-format.md, "Size limits").
      double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
      gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
      const double extent = std::max({x1 - x0, y1 - y0, z1 - z0});
      const double max_ratio = dim == 3 ? kMaxCellsPerExtent3d : kMaxCellsPerExtent2d;
      if (extent / options.size > max_ratio)
        throw InvalidInput(fmt::format("{}: mesh size {:.3g} m for a body of extent {:.3g} m; expected size >= extent/{} = "
                                       "{:.3g} m (larger meshes exceed the limit of about 2,000,000 unknowns)",
                                       name, options.size, extent, max_ratio, extent / max_ratio));
      gmsh::option::setNumber("Mesh.MeshSizeMax", options.size);
      gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    }
    gmsh_call(file, "mesh the geometry", [&] { gmsh::model::mesh::generate(dim); });
  }

  // The body's dimension: the highest one with elements.
  while (dim >= 2) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, dim);
    if (!types.empty()) break;
    --dim;
  }
  if (dim < 2)
    throw InvalidInput(fmt::format("{}: no surface or volume elements; expected a 2D mesh of quadrilaterals or a 3D "
                                   "mesh of hexahedra",
                                   name));
  const int cell_type = dim == 2 ? kGmshQuad4 : kGmshHexa8;
  const int facet_type = dim == 2 ? kGmshLine2 : kGmshQuad4;

  std::vector<int> body_entities;
  {
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, dim);
    std::set<int> entities;
    for (const auto& [d, tag] : groups) {
      std::vector<int> tags;
      gmsh::model::getEntitiesForPhysicalGroup(d, tag, tags);
      entities.insert(tags.begin(), tags.end());
    }
    body_entities.assign(entities.begin(), entities.end());
  }

  bool subdivided = false;
  auto cells_by_type = elements_of(dim, body_entities);
  const bool has_simplices = cells_by_type.count(dim == 2 ? kGmshTriangle3 : kGmshTetra4) > 0;
  if (is_geo && has_simplices) {
    // No Recombine/Transfinite in the .geo: split every simplex into quads/hexes (Gmsh's
    // subdivision), the cheapest route to the Q1 cells our kernels integrate (docs/meshes.md).
    gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", dim == 2 ? 1 : 2);
    if (dim == 2) gmsh::option::setNumber("Mesh.RecombineAll", 1);
    gmsh_call(file, "mesh the geometry with all-quad/hex subdivision", [&] {
      gmsh::model::mesh::clear();
      gmsh::model::mesh::generate(dim);
    });
    subdivided = true;
    cells_by_type = elements_of(dim, body_entities);
  }
  for (const auto& [type, block] : cells_by_type) {
    if (type == cell_type) continue;
    std::string found;
    for (const auto& [t, b] : cells_by_type)
      found += fmt::format("{}{} {}", found.empty() ? "" : ", ", b.first.size(), gmsh_type_name(t));
    throw InvalidInput(fmt::format(
        "{}: the {}D body has {}; expected only {} (frictopt's Q1 cells, docs/meshes.md: mesh the .geo with "
        "Recombine/Transfinite, or let frictopt mesh the .geo, which subdivides simplices)",
        name, dim, found, gmsh_type_name(cell_type)));
  }
  const auto cells_it = cells_by_type.find(cell_type);
  if (cells_it == cells_by_type.end() || cells_it->second.first.empty())
    throw InvalidInput(fmt::format("{}: no {} in the body; expected a {}D mesh of them", name,
                                   gmsh_type_name(cell_type), dim));
  const std::vector<std::size_t>& cell_tags = cells_it->second.first;
  const std::vector<std::size_t>& cell_nodes = cells_it->second.second;

  // Nodes: those of the body's cells, in the order of their Gmsh tags.
  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric, -1, -1, false, false);
  std::vector<std::size_t> used(cell_nodes.begin(), cell_nodes.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, int> index;  // Gmsh node tag -> our node
  index.reserve(used.size());
  for (std::size_t k = 0; k < used.size(); ++k) index.emplace(used[k], static_cast<int>(k));
  Eigen::MatrixXd X(static_cast<Eigen::Index>(used.size()), dim);
  std::vector<bool> seen(used.size(), false);
  double z_min = INFINITY, z_max = -INFINITY, extent = 0.0;
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    const auto it = index.find(node_tags[k]);
    if (it == index.end()) continue;
    for (int c = 0; c < dim; ++c) X(it->second, c) = coordinates[3 * k + static_cast<std::size_t>(c)];
    seen[static_cast<std::size_t>(it->second)] = true;
    z_min = std::min(z_min, coordinates[3 * k + 2]);
    z_max = std::max(z_max, coordinates[3 * k + 2]);
  }
  if (std::find(seen.begin(), seen.end(), false) != seen.end())
    throw InvalidInput(fmt::format("{}: a cell refers to a node the file does not define", name));
  extent = (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
  if (dim == 2 && !(z_max - z_min <= 1e-12 * std::max(extent, 1.0)))
    throw InvalidInput(fmt::format("{}: the 2D body spans z in [{}, {}]; expected a planar body in a plane z = const",
                                   name, z_min, z_max));

  const int nodes_per_cell = dim == 2 ? 4 : 8;
  Connectivity cells(static_cast<Eigen::Index>(cell_tags.size()), nodes_per_cell);
  for (std::size_t e = 0; e < cell_tags.size(); ++e)
    for (int a = 0; a < nodes_per_cell; ++a)
      cells(static_cast<Eigen::Index>(e), a) = index.at(cell_nodes[e * static_cast<std::size_t>(nodes_per_cell) +
                                                                  static_cast<std::size_t>(a)]);
  // Gmsh's and VTK's node orders of the quadrilateral and the hexahedron agree; a cell that is
  // inverted in that order (a mirrored hand-written cell) is mirrored back.
  const ElementKind kind = dim == 2 ? ElementKind::kQuad4 : ElementKind::kHex8;
  with_element(kind, [&](auto element) {
    using Element = decltype(element);
    const typename Element::Point centre = Element::Point::Zero();
    const auto G = Element::gradients(centre);
    Eigen::Matrix<double, Element::kNodes, Element::kDim> Xe;
    for (Eigen::Index e = 0; e < cells.rows(); ++e) {
      for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(cells(e, a));
      if ((Xe.transpose() * G).determinant() < 0) {
        std::swap(cells(e, 1), cells(e, 3));
        if constexpr (Element::kDim == 3) std::swap(cells(e, 5), cells(e, 7));
      }
    }
  });

  // Boundary sets: the named physical groups of dimension dim − 1.
  std::map<std::string, BoundarySet, std::less<>> boundaries;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim - 1);
  for (const auto& [d, tag] : groups) {
    const std::string group = physical_name(d, tag);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
    if (entities.empty()) continue;
    const auto facets_by_type = elements_of(dim - 1, entities);
    BoundarySet set;
    const int width = dim == 2 ? 2 : 4;
    std::vector<int> facet_nodes;
    for (const auto& [type, block] : facets_by_type) {
      if (type != facet_type)
        throw InvalidInput(fmt::format("{}: physical group '{}' has {} {}; expected only {} (faces of the body's {})",
                                       name, group, block.first.size(), gmsh_type_name(type),
                                       gmsh_type_name(facet_type), gmsh_type_name(cell_type)));
      for (std::size_t k = 0; k < block.second.size(); ++k) {
        const auto it = index.find(block.second[k]);
        if (it == index.end())
          throw InvalidInput(fmt::format("{}: physical group '{}' has a facet on Gmsh node {}, which no cell of the "
                                         "body uses; expected a group on the body's boundary",
                                         name, group, block.second[k]));
        facet_nodes.push_back(it->second);
      }
    }
    set.facets.resize(static_cast<Eigen::Index>(facet_nodes.size()) / width, width);
    for (std::size_t k = 0; k < facet_nodes.size(); ++k)
      set.facets(static_cast<Eigen::Index>(k) / width, static_cast<Eigen::Index>(k) % width) = facet_nodes[k];
    set.nodes = facet_nodes;
    std::sort(set.nodes.begin(), set.nodes.end());
    set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
    if (!boundaries.emplace(group, std::move(set)).second)
      throw InvalidInput(fmt::format("{}: two physical groups of dimension {} are called '{}'; expected distinct names",
                                     name, dim - 1, group));
  }

  ElementDiagnostics diagnostics;
  diagnostics.location = [tags = cell_tags, name](Eigen::Index e) {
    return fmt::format("Gmsh element {} of {}", tags[static_cast<std::size_t>(e)], name);
  };
  // The mesh as read must be valid before any design moves it: Gmsh can return a cell with an
  // inverted corner (seen when simplices are subdivided near a curved surface, e.g. the fillets
  // of cases3d/gmsh-die at size 0.007).
  diagnostics.inverted_hint = subdivided ? " — try another mesh size, or Recombine/Transfinite in the .geo"
                                         : " — the file's cell is not a valid hexahedron/quadrilateral";
  const Eigen::Index num_dofs = X.rows() * dim;
  const Mesh as_read(kind, X, cells, Eigen::SparseMatrix<double>(num_dofs, 0), boundaries, diagnostics);
  as_read.check_quality(X, "mesh as read");
  diagnostics.inverted_hint = " — the design moves the patch too far for the cells around it (smaller bounds or a "
                              "finer mesh near the patch)";
  Mesh mesh(kind, std::move(X), std::move(cells), Eigen::SparseMatrix<double>(num_dofs, 0), std::move(boundaries),
            std::move(diagnostics));
  return ReadResult{std::move(mesh), subdivided, cell_tags};
}

}  // namespace

GmshMesh::GmshMesh(const std::filesystem::path& file, const GmshMeshOptions& options)
    : file_(file), mesh_(ElementKind::kQuad4, Eigen::MatrixXd::Zero(0, 2), Connectivity(), Eigen::SparseMatrix<double>(), {}) {
  ReadResult result = read(file, options);
  mesh_ = std::move(result.mesh);
  subdivided_ = result.subdivided;
  element_tags_ = std::move(result.element_tags);
}

}  // namespace frictopt::mesh
