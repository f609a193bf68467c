// SPDX-License-Identifier: MIT
// A line-by-line check of a .msh file before Gmsh reads it (docs/meshes.md, "What is checked
// before Gmsh"). Gmsh's own reader of format 2.2 reads numbers with fscanf and so reads a short
// element line on into the next one, and it crashes on an element whose node the file does not
// define; both are refused here, naming the line. Format: Gmsh's reference manual, "MSH file
// format" (versions 2.2 and 4.1).
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"

namespace frictopt::mesh {
namespace {

namespace fs = std::filesystem;

// Nodes of the Gmsh element types (reference manual, "MSH file format"); 0: not a type.
int nodes_of_type(long type) {
  static constexpr int kNodes[] = {0,  2,  3,  4,  4,  8,  6,  5,  3,  6,  9,  10, 27, 18, 14, 1,
                                   8,  20, 15, 13, 9,  10, 12, 15, 15, 21, 4,  5,  6,  20, 35, 56};
  if (type >= 1 && type < static_cast<long>(std::size(kNodes))) return kNodes[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

class MshChecker {
 public:
  explicit MshChecker(const fs::path& file) : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw InvalidInput(fmt::format("{}: cannot open the mesh file", file.string()));
  }

  void run() {
    header();
    if (binary_) return;  // Gmsh reads it in the child process; only the header is ours to check
    std::string line;
    bool nodes = false, elements = false;
    while (next(line)) {
      if (line.empty()) continue;
      if (line == "$Nodes") {
        if (nodes) fail("a second $Nodes section", "one");
        version_ == 2 ? nodes22() : nodes41();
        nodes = true;
      } else if (line == "$Elements") {
        if (!nodes) fail("$Elements before $Nodes", "the $Nodes section first");
        if (elements) fail("a second $Elements section", "one");
        version_ == 2 ? elements22() : elements41();
        elements = true;
      } else if (line.size() > 1 && line[0] == '$' && line.rfind("$End", 0) != 0) {
        skip_section(line.substr(1));
      } else {
        fail(fmt::format("'{}' outside a section", shorten(line)), "a section $Name … $EndName");
      }
    }
    if (!nodes) fail("no $Nodes section", "a mesh with nodes");
    if (!elements) fail("no $Elements section", "a mesh with elements");
  }

 private:
  [[noreturn]] void fail(std::string_view what, std::string_view expected) const {
    throw InvalidInput(fmt::format("{}:{}: {}; expected {} (Gmsh MSH format {})", file_.string(), line_number_, what,
                                   expected, version_ == 2 ? "2.2" : "4.1"));
  }

  static std::string shorten(std::string_view s) {
    std::string out;
    for (char c : s.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return s.size() > 40 ? out + "…" : out;
  }

  // One line, at most kMaxLine bytes (a file of NUL bytes or without newlines is refused at
  // its first line, not read whole).
  bool next(std::string& line) {
    static constexpr std::streamsize kMaxLine = 1 << 16;
    line.resize(static_cast<std::size_t>(kMaxLine));
    in_.getline(line.data(), kMaxLine);
    const std::streamsize got = in_.gcount();
    if (got == 0 && in_.eof()) return false;
    ++line_number_;
    if (in_.fail() && !in_.eof()) fail(fmt::format("a line longer than {} bytes", kMaxLine - 1), "a Gmsh .msh text line");
    line.resize(static_cast<std::size_t>(got) - (in_.eof() ? 0 : 1));  // gcount counts the '\n' it removed
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find('\0') != std::string::npos) fail("a NUL byte", "a text line");
    return true;
  }

  std::string need(std::string_view what) {
    std::string line;
    if (!next(line)) fail(fmt::format("the end of the file where {} should be", what), std::string(what));
    return line;
  }

  static std::vector<std::string> split(std::string_view line) {
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      const std::size_t b = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      if (i > b) out.emplace_back(line.substr(b, i - b));
    }
    return out;
  }

  long integer(const std::string& s, std::string_view what, long lo) const {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (errno != 0 || end != s.c_str() + s.size() || v < lo)
      fail(fmt::format("{} '{}'", what, shorten(s)), fmt::format("an integer >= {}", lo));
    return v;
  }

  void number(const std::string& s, std::string_view what) const {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size() || !std::isfinite(v))
      fail(fmt::format("{} '{}'", what, shorten(s)), "a finite number");
  }

  std::vector<std::string> fields(const std::string& line, std::size_t count, std::string_view what) const {
    std::vector<std::string> f = split(line);
    if (f.size() != count)
      fail(fmt::format("{} with {} entries", what, f.size()), fmt::format("{} entries on the line", count));
    return f;
  }

  // A count read from the file bounds the lines still to come: each takes at least 2 bytes.
  void plausible(long count, std::string_view what) const {
    if (static_cast<std::uintmax_t>(count) > size_ / 2)
      fail(fmt::format("{} = {} in a file of {} bytes", what, count, size_), "a count the file can hold");
  }

  void header() {
    std::error_code ec;
    size_ = fs::file_size(file_, ec);
    std::string line;
    if (!next(line) || line != "$MeshFormat")
      fail("a file that does not start with $MeshFormat", "a Gmsh .msh file");
    line = need("the format line");
    const auto f = split(line);
    if (f.size() != 3 || (f[0] != "2.2" && f[0] != "4.1") || (f[1] != "0" && f[1] != "1") || f[2] != "8")
      fail(fmt::format("format line '{}'", shorten(line)), "'2.2 0 8' or '4.1 0 8' (ASCII) or '4.1 1 8' (binary)");
    version_ = f[0] == "2.2" ? 2 : 4;
    binary_ = f[1] == "1";
    if (binary_) return;
    if (need("$EndMeshFormat") != "$EndMeshFormat") fail("no $EndMeshFormat after the format line", "$EndMeshFormat");
  }

  void skip_section(const std::string& name) {
    const std::string end = "$End" + name;
    std::string line;
    while (next(line))
      if (line == end) return;
    fail(fmt::format("the end of the file inside section ${}", shorten(name)), end);
  }

  void end_of(std::string_view section) {
    const std::string line = need(section);
    if (line != section)
      fail(fmt::format("'{}' where the section ends", shorten(line)),
           fmt::format("{} (the counts at the section's start say so)", section));
  }

  void nodes22() {
    const long n = integer(fields(need("the number of nodes"), 1, "the node count line")[0], "node count", 0);
    plausible(n, "the node count");
    tags_.reserve(static_cast<std::size_t>(n));
    for (long k = 0; k < n; ++k) {
      const auto f = fields(need("a node line"), 4, "a node line (tag x y z)");
      tags_.push_back(integer(f[0], "node tag", 1));
      for (int c = 1; c < 4; ++c) number(f[static_cast<std::size_t>(c)], "coordinate");
    }
    end_of("$EndNodes");
    std::sort(tags_.begin(), tags_.end());
  }

  void check_node(const std::string& token) const {
    const long tag = integer(token, "node tag", 1);
    if (!std::binary_search(tags_.begin(), tags_.end(), tag))
      fail(fmt::format("an element on node {}, which the file does not define", tag), "nodes of the $Nodes section");
  }

  void elements22() {
    const long n = integer(fields(need("the number of elements"), 1, "the element count line")[0], "element count", 0);
    plausible(n, "the element count");
    for (long k = 0; k < n; ++k) {
      const std::string line = need("an element line");
      const auto f = split(line);
      if (f.size() < 3) fail(fmt::format("an element line with {} entries", f.size()), "tag type ntags tags… nodes…");
      (void)integer(f[0], "element tag", 1);
      const long type = integer(f[1], "element type", 1);
      const int nodes = nodes_of_type(type);
      if (nodes == 0) fail(fmt::format("element type {}", type), "a Gmsh element type (1 = line, 3 = quadrangle, 5 = hexahedron, …)");
      const long ntags = integer(f[2], "number of tags", 0);
      const std::size_t expected = 3 + static_cast<std::size_t>(ntags) + static_cast<std::size_t>(nodes);
      if (ntags > 16 || f.size() != expected)
        fail(fmt::format("an element line of type {} with {} entries", type, f.size()),
             fmt::format("3 + {} tags + {} nodes = {} entries", ntags, nodes, expected));
      for (std::size_t t = 3; t < 3 + static_cast<std::size_t>(ntags); ++t) (void)integer(f[t], "element tag", 0);
      for (std::size_t a = 3 + static_cast<std::size_t>(ntags); a < f.size(); ++a) check_node(f[a]);
    }
    end_of("$EndElements");
  }

  void nodes41() {
    const auto head = fields(need("the $Nodes counts"), 4, "the $Nodes count line (blocks nodes min max)");
    const long blocks = integer(head[0], "block count", 0), n = integer(head[1], "node count", 0);
    plausible(blocks, "the block count");
    plausible(n, "the node count");
    tags_.reserve(static_cast<std::size_t>(n));
    long total = 0;
    for (long b = 0; b < blocks; ++b) {
      const auto f = fields(need("a node block line"), 4, "a node block line (dim entity parametric count)");
      const long dim = integer(f[0], "entity dimension", 0);
      if (dim > 3) fail(fmt::format("entity dimension {}", dim), "0 to 3");
      (void)integer(f[1], "entity tag", -2147483647L);
      const long parametric = integer(f[2], "parametric flag", 0);
      if (parametric > 1) fail(fmt::format("parametric flag {}", parametric), "0 or 1");
      const long count = integer(f[3], "nodes in the block", 0);
      total += count;
      if (total > n) fail(fmt::format("blocks with more than the {} nodes announced", n), "the announced node count");
      for (long k = 0; k < count; ++k)
        tags_.push_back(integer(fields(need("a node tag"), 1, "a node tag line")[0], "node tag", 1));
      const std::size_t width = 3 + (parametric == 1 ? static_cast<std::size_t>(dim) : 0);
      for (long k = 0; k < count; ++k)
        for (const std::string& v : fields(need("node coordinates"), width, "a node coordinate line")) number(v, "coordinate");
    }
    if (total != n) fail(fmt::format("blocks with {} nodes where {} are announced", total, n), "the announced node count");
    end_of("$EndNodes");
    std::sort(tags_.begin(), tags_.end());
  }

  void elements41() {
    const auto head = fields(need("the $Elements counts"), 4, "the $Elements count line (blocks elements min max)");
    const long blocks = integer(head[0], "block count", 0), n = integer(head[1], "element count", 0);
    plausible(blocks, "the block count");
    plausible(n, "the element count");
    long total = 0;
    for (long b = 0; b < blocks; ++b) {
      const auto f = fields(need("an element block line"), 4, "an element block line (dim entity type count)");
      (void)integer(f[0], "entity dimension", 0);
      (void)integer(f[1], "entity tag", -2147483647L);
      const long type = integer(f[2], "element type", 1);
      const int nodes = nodes_of_type(type);
      if (nodes == 0) fail(fmt::format("element type {}", type), "a Gmsh element type (1 = line, 3 = quadrangle, 5 = hexahedron, …)");
      const long count = integer(f[3], "elements in the block", 0);
      total += count;
      if (total > n) fail(fmt::format("blocks with more than the {} elements announced", n), "the announced element count");
      for (long k = 0; k < count; ++k) {
        const auto e = fields(need("an element line"), 1 + static_cast<std::size_t>(nodes),
                              fmt::format("an element line of type {}", type));
        (void)integer(e[0], "element tag", 1);
        for (std::size_t a = 1; a < e.size(); ++a) check_node(e[a]);
      }
    }
    if (total != n) fail(fmt::format("blocks with {} elements where {} are announced", total, n), "the announced element count");
    end_of("$EndElements");
  }

  const fs::path& file_;
  std::ifstream in_;
  std::uintmax_t size_ = 0;
  long line_number_ = 0;
  int version_ = 4;
  bool binary_ = false;
  std::vector<long> tags_;
};

}  // namespace

void check_msh_file(const fs::path& file) { MshChecker(file).run(); }

}  // namespace frictopt::mesh
