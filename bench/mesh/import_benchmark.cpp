// SPDX-License-Identifier: MIT
// Imported bodies (docs/meshes.md, "Performance"): the cost of importing a Gmsh body and setting up
// its design extension against one state solve at about 100k unknowns, and the state solve on
// imported meshes against the structured grid of (about) equal unknowns. Medians of `repeats` runs,
// each on a fresh body (the state solve includes the symbolic analysis, as a first solve does).
//   build/bench/mesh/import_benchmark [repeats=3] [n=40]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <unistd.h>  // getpid
#include <vector>

#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "common/timing.hpp"
#include "common/punch.hpp"

namespace {

using frictopt::bench::Clock;
using frictopt::bench::seconds_since;
using frictopt::bench::median;

using namespace frictopt;
namespace fs = std::filesystem;
// Processor time of the process (all threads): on a machine shared with other jobs the wall
// time of a phase grows with the load, its processor time much less.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

study::BodyDefinition punch(int n) { return frictopt::bench::punch(n, n / 2); }

struct Timing {
  double import_s = 0, extension_s = 0, state_s = 0;       // wall
  double import_cpu = 0, extension_cpu = 0, state_cpu = 0;  // processor
  int unknowns = 0, contact_nodes = 0;
  double min_scaled_jacobian = 0;
};

// The punch with its body from `geo` (groups Bottom, Top) at mesh size `size` (NaN: the .geo's).
Timing imported(const fs::path& geo, double size, mesh::ExtensionKind extension, int n) {
  study::BodyDefinition b = punch(n);
  Timing t;
  auto start = Clock::now();
  double cpu = cpu_seconds();
  auto reference = std::make_shared<const mesh::Mesh>(mesh::GmshMesh(geo, {.size = size}).take_mesh());
  t.import_s = seconds_since(start);
  t.import_cpu = cpu_seconds() - cpu;
  study::ImportedMeshDefinition imported;
  imported.file = geo;
  imported.reference = reference;
  imported.motion.patch = "Bottom";
  imported.motion.extension = extension;
  b.imported_mesh = imported;
  b.contact_surface = "Bottom";
  b.dirichlet[0].boundary = "Top";
  start = Clock::now();
  cpu = cpu_seconds();
  const mesh::Mesh moved = mesh::with_design_motion(*reference, b.shape,
                                                    {"Bottom", mesh::PlaneFrame::standard(3), extension, {"Top"}});
  t.extension_s = seconds_since(start);
  t.extension_cpu = cpu_seconds() - cpu;
  study::ElasticBody body(b);
  start = Clock::now();
  cpu = cpu_seconds();
  const study::BodyState s = body.solve(b.initial_design);
  t.state_s = seconds_since(start);
  t.state_cpu = cpu_seconds() - cpu;
  t.unknowns = body.elasticity().dofs().num_free();
  t.contact_nodes = static_cast<int>(body.contact_boundary()->num_nodes());
  t.min_scaled_jacobian = s.min_scaled_jacobian;
  if (s.summary.status != Status::kConverged) fmt::print(stderr, "state solve: {}\n", s.summary.message);
  return t;
}

Timing structured(int n) {
  const study::BodyDefinition b = punch(n);
  study::ElasticBody body(b);
  Timing t;
  const auto start = Clock::now();
  const double cpu = cpu_seconds();
  const study::BodyState s = body.solve(b.initial_design);
  t.state_s = seconds_since(start);
  t.state_cpu = cpu_seconds() - cpu;
  t.unknowns = body.elasticity().dofs().num_free();
  t.contact_nodes = static_cast<int>(body.contact_boundary()->num_nodes());
  t.min_scaled_jacobian = s.min_scaled_jacobian;
  return t;
}

fs::path write_geo(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  const int n = argc > 2 ? std::atoi(argv[2]) : 40;
  const fs::path dir = fs::temp_directory_path() / fmt::format("frictopt-import-bench-{}", ::getpid());
  fs::create_directories(dir);
  // The structured-equivalent punch: punch.geo with n × n × n/2 layers.
  std::ifstream in(fs::path(FRICTOPT_SOURCE_DIR) / "cases3d/gmsh-punch/punch.geo");
  std::stringstream text;
  text << in.rdbuf();
  const fs::path extruded = write_geo(
      dir, "punch.geo",
      std::regex_replace(text.str(), std::regex("n1 = 16, n2 = 16, nv = 8"),
                         fmt::format("n1 = {}, n2 = {}, nv = {}", n, n, n / 2)));
  // An unstructured box of the same extents: tetrahedra subdivided into hexahedra.
  const fs::path box = write_geo(dir, "box.geo",
                                 "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 0.5};\n"
                                 "Physical Volume(\"Body\") = {1};\nPhysical Surface(\"Bottom\") = {5};\n"
                                 "Physical Surface(\"Top\") = {6};\n");
  const double box_size = std::atof(std::getenv("BOX_SIZE") ? std::getenv("BOX_SIZE") : "0.07");

  struct Row {
    std::string name;
    std::vector<Timing> runs;
  };
  std::vector<Row> rows = {{"structured grid", {}}, {"imported, extruded (sweep)", {}},
                           {"imported, extruded (laplace)", {}}, {"imported, subdivided box (laplace)", {}}};
  for (int r = 0; r < repeats; ++r) {
    rows[0].runs.push_back(structured(n));
    rows[1].runs.push_back(imported(extruded, NAN, mesh::ExtensionKind::kSweep, n));
    rows[2].runs.push_back(imported(extruded, NAN, mesh::ExtensionKind::kLaplace, n));
    rows[3].runs.push_back(imported(box, box_size, mesh::ExtensionKind::kLaplace, n));
  }
  const auto med = [](const Row& row, double Timing::*field) {
    std::vector<double> v;
    for (const Timing& t : row.runs) v.push_back(t.*field);
    return median(v);
  };
  const double structured_state = med(rows[0], &Timing::state_s);
  const double structured_cpu = med(rows[0], &Timing::state_cpu);
  fmt::print("| body | free unknowns | contact nodes | min scaled J | import [s] | extension [s] | state solve [s] | "
             "(import+extension)/state | state / structured state |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows) {
    const double imp = med(row, &Timing::import_s), ext = med(row, &Timing::extension_s),
                 st = med(row, &Timing::state_s);
    const double imp_c = med(row, &Timing::import_cpu), ext_c = med(row, &Timing::extension_cpu),
                 st_c = med(row, &Timing::state_cpu);
    // wall (processor) seconds
    fmt::print("| {} | {} | {} | {:.3f} | {:.3f} ({:.3f}) | {:.3f} ({:.3f}) | {:.2f} ({:.2f}) | {:.3f} ({:.3f}) | "
               "{:.2f} ({:.2f}) |\n",
               row.name, row.runs[0].unknowns, row.runs[0].contact_nodes, row.runs[0].min_scaled_jacobian, imp, imp_c,
               ext, ext_c, st, st_c, (imp + ext) / st, (imp_c + ext_c) / st_c, st / structured_state,
               st_c / structured_cpu);
  }
  fmt::print("medians of {} runs; n = {}; wall seconds (processor seconds, all threads)\n", repeats, n);
  fs::remove_all(dir);
  return 0;
}
