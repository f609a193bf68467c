// SPDX-License-Identifier: MIT
#include "frictopt/mesh/gmsh_mesh.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <system_error>
#include <type_traits>
#include <unordered_map>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/elements.hpp"
#include "gmsh_session.hpp"
#include "mesh_child_process.hpp"

namespace frictopt::mesh {
namespace {

// The finest .geo meshing accepted: extent/size cells along the body's largest extent.
constexpr double kMaxCellsPerExtent3d = 200.0;
constexpr double kMaxCellsPerExtent2d = 2000.0;
// The child's address space beyond the caller's: a base for Gmsh's own tables, and a share per
// unknown allowed (GmshMeshOptions::max_unknowns).
constexpr std::uint64_t kGmshBaseBytes = 256ull << 20;
constexpr std::uint64_t kGmshBytesPerUnknown = 4096;

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

using detail::GmshSession;
using detail::gmsh_call;

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

// The mesh as Gmsh gives it, in our node numbering: what the child process sends back.
struct RawMesh {
  int dim = 0;
  bool subdivided = false;
  Eigen::MatrixXd X;  // num_nodes × dim
  Connectivity cells;
  std::vector<std::size_t> cell_tags;
  std::vector<std::pair<std::string, Connectivity>> groups;  // boundary group → facets
};

// The bytes of a RawMesh through the pipe (same binary on both sides: native layout).
class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_bytes(const void* data, std::size_t size) {
    put<std::uint64_t>(size);
    bytes_.append(static_cast<const char*>(data), size);
  }
  void put_matrix(const auto& m) {
    put<std::int64_t>(m.rows());
    put<std::int64_t>(m.cols());
    put_bytes(m.data(), static_cast<std::size_t>(m.size()) * sizeof(*m.data()));
  }
  std::string take() && { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    T v;
    need(sizeof v);
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  std::string get_string() {
    const auto size = static_cast<std::size_t>(get<std::uint64_t>());
    need(size);
    std::string out = bytes_.substr(at_, size);
    at_ += size;
    return out;
  }
  template <class M>
  M get_matrix() {
    const auto rows = get<std::int64_t>(), cols = get<std::int64_t>();
    const std::string data = get_string();
    M m(rows, cols);
    if (data.size() != static_cast<std::size_t>(m.size()) * sizeof(*m.data())) fail();
    std::memcpy(m.data(), data.data(), data.size());
    return m;
  }

 private:
  void need(std::size_t n) const {
    if (at_ + n > bytes_.size()) fail();
  }
  [[noreturn]] static void fail() { throw std::runtime_error("the Gmsh child process sent a damaged mesh"); }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

std::string serialize(const RawMesh& raw) {
  Writer w;
  w.put<std::int32_t>(raw.dim);
  w.put<std::uint8_t>(raw.subdivided ? 1 : 0);
  w.put_matrix(raw.X);
  w.put_matrix(raw.cells);
  w.put_bytes(raw.cell_tags.data(), raw.cell_tags.size() * sizeof(std::size_t));
  w.put<std::uint64_t>(raw.groups.size());
  for (const auto& [name, facets] : raw.groups) {
    w.put_bytes(name.data(), name.size());
    w.put_matrix(facets);
  }
  return std::move(w).take();
}

RawMesh deserialize(const std::string& bytes) {
  Reader r(bytes);
  RawMesh raw;
  raw.dim = r.get<std::int32_t>();
  raw.subdivided = r.get<std::uint8_t>() != 0;
  raw.X = r.get_matrix<Eigen::MatrixXd>();
  raw.cells = r.get_matrix<Connectivity>();
  const std::string tags = r.get_string();
  raw.cell_tags.resize(tags.size() / sizeof(std::size_t));
  std::memcpy(raw.cell_tags.data(), tags.data(), raw.cell_tags.size() * sizeof(std::size_t));
  const auto groups = r.get<std::uint64_t>();
  for (std::uint64_t g = 0; g < groups; ++g) {
    std::string name = r.get_string();
    raw.groups.emplace_back(std::move(name), r.get_matrix<Connectivity>());
  }
  return raw;
}

// The preconditions checked in the caller's process, before Gmsh sees the file.
struct Checked {
  bool is_geo = false;
  std::vector<std::filesystem::path> sources;
};

Checked check_input(const std::filesystem::path& file, const GmshMeshOptions& options) {
  const std::string name = file.string();
  if (name.find('\0') != std::string::npos)
    throw InvalidInput(fmt::format("mesh file name with a NUL byte ('{}'); expected a file name without NUL",
                                   std::string(name.c_str())));
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
  if (!(options.max_unknowns > 0))
    throw InvalidInput(fmt::format("{}: GmshMeshOptions::max_unknowns = {}; expected > 0", name, options.max_unknowns));
  if (options.budget_unknowns < 0)
    throw InvalidInput(
        fmt::format("{}: GmshMeshOptions::budget_unknowns = {}; expected >= 0", name, options.budget_unknowns));
  if (!(options.time_limit_seconds > 0 && options.time_limit_seconds <= 1e6))
    throw InvalidInput(
        fmt::format("{}: GmshMeshOptions::time_limit_seconds = {}; expected (0, 1e6]", name, options.time_limit_seconds));
  Checked checked;
  checked.is_geo = is_geo;
  if (!is_geo) {
    check_msh_file(file);
    checked.sources = {std::filesystem::weakly_canonical(std::filesystem::absolute(file), ec)};
  } else if (options.trust_geo) {
    checked.sources = {std::filesystem::weakly_canonical(std::filesystem::absolute(file), ec)};
  } else {
    checked.sources = check_geo_file(file, options.allowed_root);
  }
  return checked;
}

// Gmsh's part, run in the child process: read (and mesh) the file, pick the body's cells and
// the boundary groups, renumber the nodes.
RawMesh extract(const std::filesystem::path& file, const GmshMeshOptions& options, bool is_geo) {
  const std::string name = file.string();
  const bool has_size = !std::isnan(options.size);
  GmshSession session;
  gmsh_call(file, "read the file", [&] { gmsh::open(name); });
  int dim = gmsh::model::getDimension();
  if (is_geo) {
    if (dim < 2)
      throw InvalidInput(fmt::format("{}: the geometry has no {}; expected a 2D surface or a 3D volume", name,
                                     dim < 0 ? "entities" : "surface or volume"));
    // Bounded before meshing, so that a mistyped size (1e-9 m) is an error and not hours of
    // Gmsh and an exhausted memory: (extent/size)^dim cells stay near the limit of
    // options.max_unknowns (docs/case-format.md, "Size limits").
    double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
    gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
    const double extent = std::max({x1 - x0, y1 - y0, z1 - z0});
    const double max_ratio = dim == 3 ? kMaxCellsPerExtent3d : kMaxCellsPerExtent2d;
    if (has_size) {
      if (extent / options.size > max_ratio)
        throw InvalidInput(fmt::format("{}: mesh size {:.3g} m for a body of extent {:.3g} m; expected size >= extent/{} = "
                                       "{:.3g} m (larger meshes exceed the limit of about 2,000,000 unknowns)",
                                       name, options.size, extent, max_ratio, extent / max_ratio));
      gmsh::option::setNumber("Mesh.MeshSizeMax", options.size);
    }
    // The sizes a .geo sets itself (points, fields) are bounded the same way: no element
    // smaller than extent/max_ratio. Transfinite counts and extrusion layers are not sizes;
    // the node count after meshing and the child's time and memory limits bound them.
    if (std::isfinite(extent) && extent > 0) gmsh::option::setNumber("Mesh.MeshSizeMin", extent / max_ratio);
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
  const bool keep_simplices = options.family == ElementFamily::kSimplex;
  int cell_type = keep_simplices ? (dim == 2 ? kGmshTriangle3 : kGmshTetra4) : (dim == 2 ? kGmshQuad4 : kGmshHexa8);
  int facet_type = dim == 2 ? kGmshLine2 : keep_simplices ? kGmshTriangle3 : kGmshQuad4;

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
  const bool only_simplices = has_simplices && cells_by_type.size() == 1;
  // With keep_simplices the simplices are the P1 cells as Gmsh made or wrote them (docs/meshes.md,
  // "Tetrahedra and triangles"); otherwise they become Q1 cells.
  if (!keep_simplices && is_geo && has_simplices) {
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
  } else if (!keep_simplices && !is_geo && only_simplices) {
    // A .msh of triangles/tetrahedra only: read as they are and subdivided by the caller
    // (subdivide_simplices), as Gmsh subdivides a .geo's.
    cell_type = dim == 2 ? kGmshTriangle3 : kGmshTetra4;
    facet_type = dim == 2 ? kGmshLine2 : kGmshTriangle3;
    subdivided = true;
  }
  for (const auto& [type, block] : cells_by_type) {
    if (type == cell_type) continue;
    std::string found;
    for (const auto& [t, b] : cells_by_type)
      found += fmt::format("{}{} {}", found.empty() ? "" : ", ", b.first.size(), gmsh_type_name(t));
    if (keep_simplices)
      throw InvalidInput(fmt::format(
          "{}: the {}D body has {}; expected only {} (mesh.element = \"{}\" keeps the file's simplices as P1 cells, "
          "docs/meshes.md: mesh the .geo without Recombine/Transfinite, or read this file with mesh.element = \"{}\")",
          name, dim, found, gmsh_type_name(cell_type), dim == 2 ? "tri3" : "tet4", dim == 2 ? "quad4" : "hex8"));
    throw InvalidInput(fmt::format(
        "{}: the {}D body has {}; expected only {} (frictopt's Q1 cells, docs/meshes.md: mesh the .geo with "
        "Recombine/Transfinite, or let frictopt mesh the .geo, which subdivides simplices; a .msh of simplices "
        "only is subdivided, or subdivide it with `gmsh -{} -setnumber Mesh.SubdivisionAlgorithm {} file.geo`; "
        "or keep simplices as P1 cells with mesh.element = \"{}\")",
        name, dim, found, gmsh_type_name(cell_type), dim, dim == 2 ? 1 : 2, dim == 2 ? "tri3" : "tet4"));
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
  const auto unknowns = static_cast<std::int64_t>(used.size()) * dim;
  if (unknowns > options.max_unknowns)
    throw InvalidInput(fmt::format("{}: the {}D body has {} nodes, {} unknowns; expected at most {} unknowns "
                                   "(docs/case-format.md, \"Size limits\")",
                                   name, dim, used.size(), unknowns, options.max_unknowns));
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

  const int nodes_per_cell = static_cast<int>(cell_nodes.size() / cell_tags.size());
  Connectivity cells(static_cast<Eigen::Index>(cell_tags.size()), nodes_per_cell);
  for (std::size_t e = 0; e < cell_tags.size(); ++e)
    for (int a = 0; a < nodes_per_cell; ++a)
      cells(static_cast<Eigen::Index>(e), a) = index.at(cell_nodes[e * static_cast<std::size_t>(nodes_per_cell) +
                                                                  static_cast<std::size_t>(a)]);

  // Boundary groups: the physical groups of dimension dim − 1.
  RawMesh raw;
  std::set<std::string> names;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim - 1);
  for (const auto& [d, tag] : groups) {
    const std::string group = physical_name(d, tag);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
    if (entities.empty()) continue;
    const auto facets_by_type = elements_of(dim - 1, entities);
    const int width = facet_type == kGmshLine2 ? 2 : facet_type == kGmshTriangle3 ? 3 : 4;
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
    if (!names.insert(group).second)
      throw InvalidInput(fmt::format("{}: two physical groups of dimension {} are called '{}'; expected distinct names",
                                     name, dim - 1, group));
    Connectivity facets(static_cast<Eigen::Index>(facet_nodes.size()) / width, width);
    for (std::size_t k = 0; k < facet_nodes.size(); ++k)
      facets(static_cast<Eigen::Index>(k) / width, static_cast<Eigen::Index>(k) % width) = facet_nodes[k];
    raw.groups.emplace_back(group, std::move(facets));
  }
  raw.dim = dim;
  raw.subdivided = subdivided;
  raw.X = std::move(X);
  raw.cells = std::move(cells);
  raw.cell_tags = cell_tags;
  return raw;
}

// Splits a simplex mesh into Q1 cells, as Gmsh's Mesh.SubdivisionAlgorithm does for a .geo:
// every triangle into 3 quadrilaterals (a vertex, its two edge midpoints, the centroid), every
// tetrahedron into 4 hexahedra (a vertex, its 3 edge midpoints, its 3 face centroids, the
// centroid); a boundary segment into 2 segments, a boundary triangle into 3 quadrilaterals
// with the same new nodes as the cells beside it. The cell tags repeat the simplex's.
void subdivide_simplices(RawMesh& raw) {
  const int dim = raw.dim;
  std::vector<Eigen::RowVectorXd> added;
  const auto base = static_cast<int>(raw.X.rows());
  std::map<std::vector<int>, int> centre_of;  // sorted vertices → node at their centroid
  const auto centre = [&](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    const auto [it, fresh] = centre_of.emplace(v, base + static_cast<int>(added.size()));
    if (fresh) {
      Eigen::RowVectorXd x = Eigen::RowVectorXd::Zero(dim);
      for (int a : v) x += raw.X.row(a);
      added.push_back(x / static_cast<double>(v.size()));
    }
    return it->second;
  };
  const Eigen::Index n = raw.cells.rows();
  Connectivity cells(n * (dim + 1), dim == 2 ? 4 : 8);
  std::vector<std::size_t> tags;
  tags.reserve(static_cast<std::size_t>(cells.rows()));
  for (Eigen::Index e = 0; e < n; ++e) {
    const auto row = raw.cells.row(e);
    for (int k = 0; k <= dim; ++k) {
      const Eigen::Index out = e * (dim + 1) + k;
      const int v = row(k), p = row((k + 1) % (dim + 1)), q = row((k + 2) % (dim + 1));
      if (dim == 2) {
        cells.row(out) << v, centre({v, p}), centre({v, p, q}), centre({v, q});
      } else {
        const int r = row((k + 3) % 4);
        cells.row(out) << v, centre({v, p}), centre({v, p, q}), centre({v, q}), centre({v, r}), centre({v, p, r}),
            centre({v, p, q, r}), centre({v, q, r});
      }
      tags.push_back(raw.cell_tags[static_cast<std::size_t>(e)]);
    }
  }
  for (auto& [name, facets] : raw.groups) {
    const int w = static_cast<int>(facets.cols());
    Connectivity split(facets.rows() * w, w == 2 ? 2 : 4);
    for (Eigen::Index f = 0; f < facets.rows(); ++f)
      for (int k = 0; k < w; ++k) {
        const int v = facets(f, k), p = facets(f, (k + 1) % w);
        if (w == 2) {
          if (k == 0) split.row(f * w) << v, centre({v, p});
          else split.row(f * w + 1) << centre({v, p}), v;
        } else {
          const int q = facets(f, (k + 2) % w);
          split.row(f * w + k) << v, centre({v, p}), centre({v, p, q}), centre({v, q});
        }
      }
    facets = std::move(split);
  }
  Eigen::MatrixXd X(base + static_cast<Eigen::Index>(added.size()), dim);
  X.topRows(base) = raw.X;
  for (std::size_t k = 0; k < added.size(); ++k) X.row(base + static_cast<Eigen::Index>(k)) = added[k];
  raw.X = std::move(X);
  raw.cells = std::move(cells);
  raw.cell_tags = std::move(tags);
}

// The caller's part: the Mesh of what the child read.
Mesh build(const std::string& name, RawMesh raw, std::int64_t max_unknowns, ElementFamily family) {
  const int dim = raw.dim;
  const ElementKind kind = element_kind(family, dim);
  if (family == ElementFamily::kTensorProduct && raw.cells.cols() == dim + 1) {
    subdivide_simplices(raw);
    const auto unknowns = static_cast<std::int64_t>(raw.X.rows()) * dim;
    if (unknowns > max_unknowns)
      throw InvalidInput(fmt::format("{}: the {}D body subdivided into Q1 cells has {} nodes, {} unknowns; expected at "
                                     "most {} unknowns (docs/case-format.md, \"Size limits\")",
                                     name, dim, raw.X.rows(), unknowns, max_unknowns));
    std::vector<bool> in_cell(static_cast<std::size_t>(raw.X.rows()), false);
    for (Eigen::Index k = 0; k < raw.cells.size(); ++k) in_cell[static_cast<std::size_t>(raw.cells.data()[k])] = true;
    for (const auto& [group, facets] : raw.groups)
      for (Eigen::Index k = 0; k < facets.size(); ++k)
        if (!in_cell[static_cast<std::size_t>(facets.data()[k])])
          throw InvalidInput(fmt::format("{}: physical group '{}' has a facet that is not a face of the body's cells; "
                                         "expected a group on the body's boundary",
                                         name, group));
  }
  Eigen::MatrixXd X = std::move(raw.X);
  Connectivity cells = std::move(raw.cells);
  // Gmsh's and VTK's node orders of the quadrilateral, hexahedron, triangle and tetrahedron
  // agree; a cell that is inverted in that order (a mirrored hand-written cell, or Gmsh's
  // orientation of a volume's simplices) is mirrored back.
  with_element(kind, [&](auto element) {
    using Element = decltype(element);
    const auto G = Element::gradients(Element::centre());
    Eigen::Matrix<double, Element::kNodes, Element::kDim> Xe;
    for (Eigen::Index e = 0; e < cells.rows(); ++e) {
      for (int a = 0; a < Element::kNodes; ++a) Xe.row(a) = X.row(cells(e, a));
      if ((Xe.transpose() * G).determinant() < 0) {
        if constexpr (is_simplex(Element::kKind)) {
          std::swap(cells(e, 1), cells(e, 2));
        } else {
          std::swap(cells(e, 1), cells(e, 3));
          if constexpr (Element::kDim == 3) std::swap(cells(e, 5), cells(e, 7));
        }
      }
    }
  });

  std::map<std::string, BoundarySet, std::less<>> boundaries;
  for (auto& [group, facets] : raw.groups) {
    BoundarySet set;
    set.nodes.assign(facets.data(), facets.data() + facets.size());
    std::sort(set.nodes.begin(), set.nodes.end());
    set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
    set.facets = std::move(facets);
    boundaries.emplace(group, std::move(set));
  }

  ElementDiagnostics diagnostics;
  diagnostics.location = [tags = raw.cell_tags, name](Eigen::Index e) {
    return fmt::format("Gmsh element {} of {}", tags[static_cast<std::size_t>(e)], name);
  };
  // The mesh as read must be valid before any design moves it: Gmsh can return a cell with an
  // inverted corner (seen when simplices are subdivided near a curved surface, e.g. the fillets
  // of cases3d/gmsh-die at size 0.007).
  diagnostics.inverted_hint = raw.subdivided ? " — try another mesh size, or Recombine/Transfinite in the .geo"
                              : is_simplex(kind) ? " — the file's cell is not a valid tetrahedron/triangle"
                                                 : " — the file's cell is not a valid hexahedron/quadrilateral";
  const Eigen::Index num_dofs = X.rows() * dim;
  const Mesh as_read(kind, X, cells, Eigen::SparseMatrix<double>(num_dofs, 0), boundaries, diagnostics);
  as_read.check_quality(X, "mesh as read");
  diagnostics.inverted_hint = " — the design moves the patch too far for the cells around it (smaller bounds or a "
                              "finer mesh near the patch)";
  return Mesh(kind, std::move(X), std::move(cells), Eigen::SparseMatrix<double>(num_dofs, 0), std::move(boundaries),
              std::move(diagnostics));
}

std::atomic<bool>& trust_geo_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

}  // namespace

bool trust_geo_by_default() { return trust_geo_flag().load(); }
void set_trust_geo_by_default(bool trust) { trust_geo_flag().store(trust); }

GmshMesh::GmshMesh(const std::filesystem::path& file, const GmshMeshOptions& options)
    : file_(file), mesh_(ElementKind::kQuad4, Eigen::MatrixXd::Zero(0, 2), Connectivity(), Eigen::SparseMatrix<double>(), {}) {
  const Checked checked = check_input(file, options);
  detail::ChildLimits limits;
  limits.seconds = options.time_limit_seconds;
  // Gmsh's memory for a mesh within the unknowns limit (measured: well below 1 KB per unknown
  // for the subdivided box of docs/meshes.md), with room: a .geo whose own sizes or
  // Transfinite counts ask for far more cells ends in the child's allocation failure.
  const std::int64_t sized_for =
      options.budget_unknowns > 0 ? std::min(options.budget_unknowns, options.max_unknowns) : options.max_unknowns;
  const std::uint64_t budget = kGmshBaseBytes + kGmshBytesPerUnknown * static_cast<std::uint64_t>(sized_for);
  const std::uint64_t available = available_memory_bytes();
  limits.memory_bytes = available > 0 ? std::min(available, budget) : budget;
  limits.memory_hint = fmt::format("the limit of {} unknowns{} gives Gmsh {:.2g} GB", sized_for,
                                   sized_for < options.max_unknowns ? " (those whose solve fits the memory limit)" : "",
                                   static_cast<double>(limits.memory_bytes) / 1e9);
  const bool is_geo = checked.is_geo;
  std::string bytes = detail::run_in_child(file.string(), limits,
                                           [&] { return serialize(extract(file, options, is_geo)); });
  RawMesh raw = deserialize(bytes);
  bytes.clear();
  subdivided_ = raw.subdivided;
  element_tags_ = raw.cell_tags;
  source_files_ = checked.sources;
  mesh_ = build(file.string(), std::move(raw), options.max_unknowns, options.family);
}

std::uint64_t available_memory_bytes() {
  std::uint64_t available = 0;
  if (std::ifstream meminfo("/proc/meminfo"); meminfo) {
    std::string key;
    std::uint64_t kb = 0;
    std::string unit;
    while (meminfo >> key >> kb) {
      std::getline(meminfo, unit);
      if (key == "MemAvailable:") {
        available = kb * 1024;
        break;
      }
    }
  }
  // A cgroup (container) limit below the machine's memory.
  if (std::ifstream max("/sys/fs/cgroup/memory.max"); max) {
    std::string text;
    max >> text;
    std::uint64_t current = 0;
    if (std::ifstream now("/sys/fs/cgroup/memory.current"); now) now >> current;
    if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos && text.size() < 20) {
      const std::uint64_t limit = std::stoull(text);
      const std::uint64_t left = limit > current ? limit - current : 0;
      if (available == 0 || left < available) available = left;
    }
  }
  return available;
}

}  // namespace frictopt::mesh
