// SPDX-License-Identifier: MIT
// What a Gmsh file may do to the process that reads it (docs/meshes.md, "A .geo file runs no
// code", "Gmsh in a child process", "What is checked before Gmsh"): each test is a reproducer of
// an adversarial input — a .geo that runs the shell, writes files, ends the process or reads
// forever; a .msh that crashes Gmsh or is read on past a short line; a file of NUL bytes.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "common/invalid_input.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"

namespace frictopt::mesh {
namespace {

namespace fs = std::filesystem;
using testing::invalid_input_message;
const fs::path kData = fs::path(FRICTOPT_SOURCE_DIR) / "tests/mesh/data";

// The 2D plate of plate.geo, as text to which a test adds one line.
const std::string kPlate = R"(Point(1) = {0, 0, 0};
line[] = Extrude {2, 0, 0} { Point{1}; Layers{4}; };
surface[] = Extrude {0, 1, 0} { Curve{line[1]}; Layers{2}; Recombine; };
Physical Surface("Body") = {surface[1]};
Physical Curve("Bottom") = {line[1]};
Physical Curve("Top") = {surface[0]};
)";

class GmshSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("frictopt_gmsh_safety_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

  fs::path dir_;
};

// --- A .geo runs no code ------------------------------------------------------------------

TEST_F(GmshSafety, SystemInAGeoIsRefusedAndNothingRuns) {
  const fs::path marker = dir_ / "PWNED";
  const fs::path geo = write("body.geo", kPlate + "System \"touch " + marker.string() + "\";\n");
  const std::string message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("body.geo:7: the .geo uses 'System', which runs a shell command"), std::string::npos)
      << message;
  EXPECT_NE(message.find("--trust-geo"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(marker));
  // The explicit opt-in runs the file as it is (in the child process).
  GmshMeshOptions trusted;
  trusted.trust_geo = true;
  EXPECT_NO_THROW(GmshMesh(geo, trusted));
  EXPECT_TRUE(fs::exists(marker));
}

TEST_F(GmshSafety, EveryCommandThatReachesOutsideIsRefused) {
  const std::pair<std::string, std::string> cases[] = {
      {"SystemCall \"ls\";", "'SystemCall'"},
      {"NonBlockingSystemCall \"ls\";", "'NonBlockingSystemCall'"},
      {"OnelabRun(\"x\", \"ls\");", "'OnelabRun'"},
      {"Exit;", "'Exit', which ends the process"},
      {"Abort;", "'Abort'"},
      {"Save \"out.msh\";", "'Save', which writes a file"},
      {"Print \"out.png\";", "'Print', which writes a file"},
      {"Printf(\"%g\", 1) > \"out.txt\";", "'Printf(...) >', which writes a file"},
      {"Printf(\"%g\", 1) >> \"out.txt\";", "'Printf(...) >>', which writes a file"},
      {"Sleep 1e9;", "'Sleep'"},
      {"General.SaveOptions = 1;", "'General'"},
      {"Solver.Executable0 = \"sh\";", "'Solver'"},
      {"SetNumber(\"General.SaveSession\", 1);", "'SetNumber'"},
      {"Plugin(NewView).Run;", "'Plugin'"},
      {"CreateDir \"x\";", "'CreateDir'"},
      {"Delete Model; DeleteFile \"x\";", "'DeleteFile'"},
      // A macro is scanned like any text: Call cannot hide a command.
      {"Macro M System \"ls\"; Return Call M;", "'System'"},
      {"Function F Exit; Return Call StrCat(\"F\", \"\");", "'Exit'"},
  };
  for (const auto& [line, expected] : cases) {
    const fs::path geo = write("body.geo", kPlate + line + "\n");
    const std::string message = invalid_input_message([&] { GmshMesh{geo}; });
    EXPECT_NE(message.find("body.geo:7: "), std::string::npos) << line << " → " << message;
    EXPECT_NE(message.find(expected), std::string::npos) << line << " → " << message;
  }
}

TEST_F(GmshSafety, CommentsStringsAndHarmlessPrintsAreAllowed) {
  const fs::path geo = write("body.geo", kPlate +
                                            "// System \"touch x\";\n/* Exit;\n Save \"x\"; */\n"
                                            "Printf(\"System %g > 1\", 2 > 1);\nMesh.Algorithm = 6;\n"
                                            "Geometry.Tolerance = 1e-8;\nx = 'Exit; System';\n");
  const GmshMesh gmsh(geo);
  EXPECT_EQ(gmsh.mesh().num_elements(), 8);
}

TEST_F(GmshSafety, IncludeAndMergeNameLiteralFilesInsideTheCaseFolder) {
  // An included file is scanned too, and named with its line.
  write("parts/evil.geo", "x = 1;\nSystem \"ls\";\n");
  fs::path geo = write("body.geo", kPlate + "Include \"parts/evil.geo\";\n");
  std::string message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("evil.geo:2: the .geo uses 'System'"), std::string::npos) << message;

  geo = write("body.geo", kPlate + "Merge \"/dev/zero\";\n");
  message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("body.geo:7: Merge \"/dev/zero\" names a file outside"), std::string::npos) << message;

  geo = write("body.geo", kPlate + "Include \"../../../etc/passwd\";\n");
  message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("names a file outside"), std::string::npos) << message;

  write("data.txt", "1 2 3\n");
  geo = write("body.geo", kPlate + "Merge \"data.txt\";\n");
  message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("expected a mesh or geometry file"), std::string::npos) << message;

  geo = write("body.geo", kPlate + "Include StrCat(\"parts/\", \"evil.geo\");\n");
  message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("body.geo:7: Include with an argument that is not one string literal"), std::string::npos)
      << message;

  write("a.geo", "Include \"b.geo\";\n");
  write("b.geo", "Include \"a.geo\";\n");
  geo = write("body.geo", kPlate + "Include \"a.geo\";\n");
  message = invalid_input_message([&] { GmshMesh{geo}; });
  EXPECT_NE(message.find("includes itself"), std::string::npos) << message;

  // A harmless include is read, and listed among the mesh's sources.
  write("parts/size.geo", "n = 4;\n");
  geo = write("body.geo", "Include \"parts/size.geo\";\n" + kPlate);
  const GmshMesh gmsh(geo);
  ASSERT_EQ(gmsh.source_files().size(), 2u);
  EXPECT_EQ(gmsh.source_files()[1].filename(), "size.geo");
}

TEST_F(GmshSafety, UnterminatedStringOrCommentIsRefused) {
  fs::path geo = write("body.geo", kPlate + "x = \"abc;\nSystem \"ls\";\n");
  EXPECT_NE(invalid_input_message([&] { GmshMesh{geo}; }).find("body.geo:8: a string without its closing quote"),
            std::string::npos);
  geo = write("body.geo", kPlate + "/* open\n");
  EXPECT_NE(invalid_input_message([&] { GmshMesh{geo}; }).find("body.geo:7: a comment"), std::string::npos);
}

// --- Gmsh in a child process ----------------------------------------------------------------

TEST_F(GmshSafety, ExitInATrustedGeoEndsTheChildNotTheCaller) {
  const fs::path geo = write("body.geo", kPlate + "Exit;\n");
  GmshMeshOptions trusted;
  trusted.trust_geo = true;
  const std::string message = invalid_input_message([&] { GmshMesh(geo, trusted); });
  EXPECT_NE(message.find("Gmsh ended the process"), std::string::npos) << message;
}

TEST_F(GmshSafety, GmshCrashIsInvalidInput) {
  // Gmsh 4.8 segfaults meshing an OpenCASCADE surface with Mesh.Algorithm = 8.
  const fs::path geo = write("occ.geo",
                             "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0, 0, 0, 1, 1};\nMesh.Algorithm = 8;\n"
                             "Mesh.RecombineAll = 1;\nPhysical Surface(\"Body\") = {1};\n"
                             "Physical Curve(\"Bottom\") = {1};\n");
  const std::string message = invalid_input_message([&] { GmshMesh{geo}; });
#if defined(FRICTOPT_ADDRESS_SANITIZER)
  // Under AddressSanitizer the child's SIGSEGV is caught and reported by the sanitizer, which
  // ends the process with a status instead of the signal: still a refused file, not a crash.
  EXPECT_NE(message.find("occ.geo: Gmsh"), std::string::npos) << message;
#else
  EXPECT_NE(message.find("occ.geo: Gmsh crashed (signal 11 SIGSEGV)"), std::string::npos) << message;
#endif
}

TEST_F(GmshSafety, AGeoThatDoesNotEndIsStoppedAtTheTimeLimit) {
  const fs::path geo = write("loop.geo", "For i In {1:1e12}\n x = i;\nEndFor\n" + kPlate);
  GmshMeshOptions options;
  options.time_limit_seconds = 2;
  const auto start = std::chrono::steady_clock::now();
  const std::string message = invalid_input_message([&] { GmshMesh(geo, options); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(message.find("loop.geo: Gmsh did not finish within 2 s"), std::string::npos) << message;
  EXPECT_LT(seconds, 10.0);
}

// --- Sizes ----------------------------------------------------------------------------------

TEST_F(GmshSafety, SizesSetByTheGeoItselfAreBounded) {
#if defined(FRICTOPT_ADDRESS_SANITIZER)
  // The child's memory limit is an address-space limit, which AddressSanitizer's shadow memory
  // makes meaningless (and its instrumented meshing takes minutes); the normal build tests it.
  GTEST_SKIP() << "address-space limits under AddressSanitizer";
#endif
  // A 1 × 1 square whose points ask for 1e-7 m elements (10^14 triangles): the reader's size
  // floor extent/2000 keeps it near 2000 × 2000 cells, and the child's memory budget of the
  // unknowns limit ends it long before.
  const fs::path geo = write("tiny.geo",
                             "lc = 1e-7;\nPoint(1) = {0, 0, 0, lc};\nPoint(2) = {1, 0, 0, lc};\nPoint(3) = {1, 1, 0, lc};\n"
                             "Point(4) = {0, 1, 0, lc};\nLine(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\n"
                             "Line(4) = {4, 1};\nCurve Loop(1) = {1, 2, 3, 4};\nPlane Surface(1) = {1};\n"
                             "Physical Surface(\"Body\") = {1};\nPhysical Curve(\"Bottom\") = {1};\n");
  GmshMeshOptions options;
  options.max_unknowns = 20'000;
  const auto start = std::chrono::steady_clock::now();
  const std::string message = invalid_input_message([&] { GmshMesh(geo, options); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(message.find("tiny.geo: Gmsh "), std::string::npos) << message;
  EXPECT_NE(message.find("the limit of 20000 unknowns gives Gmsh 0.35 GB"), std::string::npos) << message;
  EXPECT_LT(seconds, 60.0);
}

TEST_F(GmshSafety, TheUnknownsLimitAppliesToAMsh) {
  GmshMeshOptions options;
  options.max_unknowns = 40;
  const std::string message = invalid_input_message([&] { GmshMesh(kData / "block41.msh", options); });
  EXPECT_NE(message.find("has 18 nodes, 54 unknowns; expected at most 40 unknowns"), std::string::npos) << message;
}

// --- What is checked before Gmsh --------------------------------------------------------------

TEST_F(GmshSafety, ElementOnAMissingNodeIsRefusedBeforeGmsh) {
  std::ifstream in(kData / "block22.msh");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string line = "1 3 2 2 5 1 9 17 11";
  text.replace(text.find(line), line.size(), "1 3 2 2 5 1 9 17 99");
  const fs::path msh = write("missing.msh", text);
  const std::string message = invalid_input_message([&] { GmshMesh{msh}; });
  EXPECT_NE(message.find("missing.msh:37: an element on node 99, which the file does not define"), std::string::npos)
      << message;
}

TEST_F(GmshSafety, ShortElementLineIsRefusedNotReadIntoTheNextLine) {
  std::ifstream in(kData / "block22.msh");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string line = "1 3 2 2 5 1 9 17 11";
  text.replace(text.find(line), line.size(), "1 3 2 2 5 1 9 17");
  const fs::path msh = write("short.msh", text);
  const std::string message = invalid_input_message([&] { GmshMesh{msh}; });
  EXPECT_NE(message.find("short.msh:37: an element line of type 3 with 8 entries; expected 3 + 2 tags + 4 nodes = 9"),
            std::string::npos)
      << message;
}

TEST_F(GmshSafety, AFileOfNulBytesIsRefusedAtOnce) {
  const fs::path msh = dir_ / "zeros.msh";
  { std::ofstream(msh, std::ios::binary); }
  fs::resize_file(msh, 2'000'000'000);  // sparse: 2 GB of NUL bytes without writing them
  const auto start = std::chrono::steady_clock::now();
  const std::string message = invalid_input_message([&] { GmshMesh{msh}; });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(message.find("zeros.msh:1: "), std::string::npos) << message;
  EXPECT_NE(message.find("expected a Gmsh .msh"), std::string::npos) << message;
  EXPECT_LT(seconds, 5.0);
}

TEST_F(GmshSafety, NonRegularFilesAndNulInTheNameAreRefused) {
  const fs::path fifo = dir_ / "fifo.msh";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(invalid_input_message([&] { GmshMesh{fifo}; }).find("not a regular file"), std::string::npos);
  const std::string name = (kData / "block41.msh").string() + std::string(1, '\0') + ".geo";
  EXPECT_NE(invalid_input_message([&] { GmshMesh{fs::path(name)}; }).find("NUL"), std::string::npos);
}

// --- A .msh of simplices --------------------------------------------------------------------

TEST_F(GmshSafety, TetrahedraOfAMshAreSubdividedIntoHexahedra) {
  const GmshMesh gmsh(kData / "tetra22.msh");
  const Mesh& mesh = gmsh.mesh();
  EXPECT_TRUE(gmsh.subdivided());
  EXPECT_EQ(mesh.element_kind(), ElementKind::kHex8);
  EXPECT_EQ(mesh.num_elements(), 4);
  EXPECT_EQ(mesh.num_nodes(), 15);  // 4 vertices, 6 edge midpoints, 4 face centroids, 1 centroid
  EXPECT_NEAR(mesh.volume(mesh.reference_positions()), 1.0 / 6.0, 1e-15);
  EXPECT_EQ(mesh.boundary("Bottom").facets.rows(), 3);
  EXPECT_EQ(mesh.boundary("Bottom").nodes.size(), 7u);
  for (int node : mesh.boundary("Bottom").nodes) EXPECT_EQ(mesh.reference_positions()(node, 2), 0.0);
  EXPECT_GT(mesh.min_scaled_jacobian(mesh.reference_positions()), 0.0);
}

}  // namespace
}  // namespace frictopt::mesh
