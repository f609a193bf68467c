// SPDX-License-Identifier: MIT
// The restricted reading of a .geo file (docs/meshes.md, "A .geo file runs no code"): a scanner
// with the tokens of Gmsh's own lexer (Gmsh's Parser/Gmsh.l: `//` and `/* */` comments,
// strings between "" or '' without escapes, identifiers [A-Za-z_][A-Za-z0-9_]*) that refuses
// every command which reaches outside the geometry — the shell, the file system, the process —
// and every file argument it cannot read as a literal. Conservative by construction: a
// forbidden name is refused wherever it stands outside strings and comments, so a macro
// (Macro/Function … Return, called with Call) cannot hide one, and a command name cannot be
// computed (Gmsh's grammar takes a command's name as a bare identifier; StrCat/Sprintf make
// strings, which are refused as file arguments).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"

namespace frictopt::mesh {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxIncludeDepth = 16;
constexpr std::uintmax_t kMaxGeoBytes = 64u << 20;  // a .geo describes a geometry: 64 MB is far beyond any

// Names refused wherever they stand (outside strings and comments), with the reason.
struct Forbidden {
  std::string_view name;
  std::string_view why;
};
constexpr std::array kForbidden{
    Forbidden{"System", "runs a shell command"},
    Forbidden{"SystemCall", "runs a shell command"},
    Forbidden{"NonBlockingSystemCall", "runs a shell command"},
    Forbidden{"Shell", "runs a shell command"},
    Forbidden{"OnelabRun", "runs a program"},
    Forbidden{"OnelabAction", "acts on the ONELAB server"},
    Forbidden{"SendToServer", "sends to a server"},
    Forbidden{"Exit", "ends the process"},
    Forbidden{"Abort", "ends the process"},
    Forbidden{"Save", "writes a file"},
    Forbidden{"Print", "writes a file"},
    Forbidden{"CreateDir", "creates a directory"},
    Forbidden{"CreateDirectory", "creates a directory"},
    Forbidden{"DeleteFile", "deletes a file"},
    Forbidden{"RenameFile", "renames a file"},
    Forbidden{"Sleep", "waits"},
    Forbidden{"Plugin", "runs a Gmsh plugin (plugins read and write files)"},
    Forbidden{"SetNumber", "sets any option by name"},
    Forbidden{"SetString", "sets any option by name"},
    Forbidden{"ListFromFile", "reads an arbitrary file"},
    Forbidden{"NewModel", "replaces the model"},
    // Option categories other than Geometry.* and Mesh.*: General.* holds the options that
    // write files at exit (SaveOptions, SaveSession) and the executables, Solver.* runs programs.
    Forbidden{"General", "sets General.* options (files written at exit, executables)"},
    Forbidden{"Solver", "sets Solver.* options (programs run)"},
    Forbidden{"PostProcessing", "sets PostProcessing.* options"},
    Forbidden{"View", "uses post-processing views"},
    Forbidden{"Fltk", "sets Fltk.* options"},
};

// The kinds of files Merge may name: meshes and geometries (a merged .geo is checked too).
bool mergeable(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".msh" || ext == ".geo" || ext == ".step" || ext == ".stp" || ext == ".brep" || ext == ".iges" ||
         ext == ".igs";
}

bool is_geo(const fs::path& p) { return p.extension() == ".geo"; }

enum class Kind { kIdentifier, kString, kOther };

struct Token {
  Kind kind;
  std::string text;  // identifier, string contents, or the punctuation ("> ", ">>", ";", ...)
  int line;
};

class Scanner {
 public:
  Scanner(const fs::path& file, std::string text) : file_(file), text_(std::move(text)) {}

  std::vector<Token> tokens() {
    std::vector<Token> out;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (c == '/' && peek(1) == '/') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == '/' && peek(1) == '*') {
        const int start = line_;
        pos_ += 2;
        for (;;) {
          if (pos_ >= text_.size())
            fail(start, "a comment /* … without its */", "a closed comment (Gmsh would read the rest as commented)");
          if (text_[pos_] == '\n') ++line_;
          if (text_[pos_] == '*' && peek(1) == '/') {
            pos_ += 2;
            break;
          }
          ++pos_;
        }
      } else if (c == '"' || c == '\'') {
        const int start = line_;
        const std::size_t begin = ++pos_;
        while (pos_ < text_.size() && text_[pos_] != c) {
          if (text_[pos_] == '\n') ++line_;
          ++pos_;
        }
        if (pos_ >= text_.size()) fail(start, "a string without its closing quote", "a closed string");
        out.push_back({Kind::kString, text_.substr(begin, pos_ - begin), start});
        ++pos_;
      } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
        const std::size_t begin = pos_;
        while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
        out.push_back({Kind::kIdentifier, text_.substr(begin, pos_ - begin), line_});
      } else if (c == '\0') {
        fail(line_, "a NUL byte", "a text file");
      } else if (c == '>' && peek(1) == '>') {
        out.push_back({Kind::kOther, ">>", line_});
        pos_ += 2;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else {
        out.push_back({Kind::kOther, std::string(1, c), line_});
        ++pos_;
      }
    }
    return out;
  }

  [[noreturn]] void fail(int line, std::string_view what, std::string_view expected) const {
    throw InvalidInput(fmt::format("{}:{}: {}; expected {}", file_.string(), line, what, expected));
  }

 private:
  char peek(std::size_t ahead) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }

  const fs::path& file_;
  std::string text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

std::string read_text(const fs::path& file, const fs::path& named_in, int line) {
  std::error_code ec;
  const auto where = [&] { return named_in.empty() ? file.string() : fmt::format("{}:{}", named_in.string(), line); };
  if (!fs::is_regular_file(file, ec))
    throw InvalidInput(fmt::format("{}: {} is not a regular file; expected a .geo text file", where(), file.string()));
  const auto bytes = fs::file_size(file, ec);
  if (ec || bytes > kMaxGeoBytes)
    throw InvalidInput(fmt::format("{}: {} has {} bytes; expected a .geo file of at most {} bytes", where(),
                                   file.string(), ec ? 0 : bytes, kMaxGeoBytes));
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof())
    throw InvalidInput(fmt::format("{}: cannot read {}", where(), file.string()));
  return text;
}

bool inside(const fs::path& file, const fs::path& root) {
  const auto [root_end, file_it] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  return root_end == root.end();
}

class GeoGuard {
 public:
  explicit GeoGuard(fs::path root) : root_(std::move(root)) {}

  void check(const fs::path& file, const fs::path& named_in, int named_line, int depth) {
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(fs::absolute(file), ec);
    if (ec) throw InvalidInput(fmt::format("{}: cannot resolve the path", file.string()));
    if (!visiting_.insert(canonical).second)
      throw InvalidInput(fmt::format("{}:{}: {} includes itself (directly or through other files); expected no cycle",
                                     named_in.string(), named_line, file.string()));
    if (depth > kMaxIncludeDepth)
      throw InvalidInput(fmt::format("{}:{}: Includes nested deeper than {}; expected at most {} levels",
                                     named_in.string(), named_line, kMaxIncludeDepth, kMaxIncludeDepth));
    files_.push_back(canonical);
    Scanner scanner(file, read_text(canonical, named_in, named_line));
    const std::vector<Token> tokens = scanner.tokens();
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      const Token& t = tokens[k];
      if (t.kind != Kind::kIdentifier) continue;
      const auto bad = std::find_if(kForbidden.begin(), kForbidden.end(), [&](const Forbidden& f) { return f.name == t.text; });
      if (bad != kForbidden.end())
        refuse(file, t.line, t.text, fmt::format("{}", bad->why));
      if (t.text == "Printf") check_printf(file, tokens, k);
      if (t.text == "Include" || t.text == "Merge" || t.text == "MergeWithBoundingBox" || t.text == "ShapeFromFile")
        check_file_argument(file, tokens, k, depth);
    }
    visiting_.erase(canonical);
  }

  std::vector<fs::path> files() && { return std::move(files_); }

 private:
  [[noreturn]] static void refuse(const fs::path& file, int line, std::string_view command, std::string_view why) {
    throw InvalidInput(fmt::format(
        "{}:{}: the .geo uses '{}', which {}; expected a .geo that only describes a geometry and its mesh "
        "(frictopt reads .geo files restricted, docs/meshes.md; run with --trust-geo, or trust_geo=True in Python, "
        "only for a file you have read and trust)",
        file.string(), line, command, why));
  }

  // Printf("…", …) prints (to nowhere: Gmsh's terminal is off); Printf(…) > "file" and >> "file"
  // write. Refused: a '>' or '>>' outside the parentheses before the statement's ';'.
  static void check_printf(const fs::path& file, const std::vector<Token>& tokens, std::size_t k) {
    int depth = 0;
    for (std::size_t j = k + 1; j < tokens.size(); ++j) {
      const Token& t = tokens[j];
      if (t.kind != Kind::kOther) continue;
      if (t.text == "(" || t.text == "[" || t.text == "{") ++depth;
      if (t.text == ")" || t.text == "]" || t.text == "}") --depth;
      if (t.text == ";" && depth <= 0) return;
      if ((t.text == ">" || t.text == ">>") && depth <= 0)
        refuse(file, tokens[k].line, "Printf(...) " + t.text, "writes a file");
    }
  }

  // Include "f"; Merge "f"; ShapeFromFile("f"): the argument must be one string literal naming
  // a file inside the root; a .geo is checked in turn.
  void check_file_argument(const fs::path& file, const std::vector<Token>& tokens, std::size_t k, int depth) {
    const Token& command = tokens[k];
    std::size_t j = k + 1;
    const bool call = command.text == "ShapeFromFile";
    if (call && (j >= tokens.size() || tokens[j].text != "(")) return;  // not a call: nothing is read
    if (call) ++j;
    const bool literal = j < tokens.size() && tokens[j].kind == Kind::kString && j + 1 < tokens.size() &&
                         tokens[j + 1].kind == Kind::kOther && tokens[j + 1].text == (call ? ")" : ";");
    if (!literal)
      throw InvalidInput(fmt::format("{}:{}: {} with an argument that is not one string literal; expected {} \"file\" "
                                     "(a computed file name cannot be checked; --trust-geo runs the file unchecked)",
                                     file.string(), command.line, command.text, command.text));
    const std::string& name = tokens[j].text;
    fs::path target(name);
    if (target.is_relative()) target = file.parent_path() / target;  // Gmsh's FixRelativePath
    std::error_code ec;
    target = fs::weakly_canonical(fs::absolute(target), ec);
    if (ec || !inside(target, root_))
      throw InvalidInput(fmt::format("{}:{}: {} \"{}\" names a file outside {}; expected a file in the case's folder "
                                     "(or below it)",
                                     file.string(), command.line, command.text, name, root_.string()));
    if (command.text == "Include") {
      check(target, file, command.line, depth + 1);
      return;
    }
    if (!mergeable(target))
      throw InvalidInput(fmt::format("{}:{}: {} \"{}\"; expected a mesh or geometry file (.msh, .geo, .step, .stp, "
                                     ".brep, .iges, .igs)",
                                     file.string(), command.line, command.text, name));
    if (!fs::is_regular_file(target, ec))
      throw InvalidInput(fmt::format("{}:{}: {} \"{}\" is not a regular file; expected a file in the case's folder",
                                     file.string(), command.line, command.text, name));
    if (is_geo(target)) {
      check(target, file, command.line, depth + 1);
    } else {
      if (target.extension() == ".msh") check_msh_file(target);
      files_.push_back(target);
    }
  }

  fs::path root_;
  std::set<fs::path> visiting_;
  std::vector<fs::path> files_;
};

}  // namespace

std::vector<fs::path> check_geo_file(const fs::path& file, const fs::path& allowed_root) {
  std::error_code ec;
  fs::path root = allowed_root.empty() ? fs::absolute(file, ec).parent_path() : allowed_root;
  root = fs::weakly_canonical(fs::absolute(root, ec), ec);
  GeoGuard guard(root);
  guard.check(file, {}, 0, 0);
  return std::move(guard).files();
}

}  // namespace frictopt::mesh
