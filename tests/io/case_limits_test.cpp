// SPDX-License-Identifier: MIT
// The case parser refuses, up front and naming the field, sizes
// beyond the documented limits (with a memory estimate, never a wrapped count), values
// outside the physical bounds, a mesh without free unknowns above the contact surface, a load
// on a face fixed in the loaded component, bad output names; it reports an empty file as
// empty and skips a byte order mark as the measurement reader does.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "common/case_text.hpp"
#include "common/invalid_case.hpp"
#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/measurements.hpp"

namespace frictopt::io {
namespace {

using testing::block_header_3d;
using testing::design_table;
using testing::expect_invalid_case;
using testing::replaced;
using testing::top_dirichlet;

constexpr std::string_view kCase2d = R"(
[geometry]
dim = 2
a = 2.0
height = 1.0

[mesh]
cells = [29, 14]

[material]
young = 2.1e11
poisson = 0.3

[[load]]
face = "top"
traction = [0.0, -2.0e7]

[[dirichlet]]
face = "left"

[design]
control_points = [15]
initial = 0.05
upper_bound = 0.75

[contact]
[contact.friction]
kind = "isotropic"
mu = 0.3
)";

const std::string kCase3d = block_header_3d("1", "0.5") + top_dirichlet("[1.0e-4, 0.0, -1.2e-3]") +
                            design_table("[4, 4]", "0.0", "0.1") + R"(
[contact]
[contact.friction]
kind = "isotropic"
mu = 0.3
)";



TEST(CaseLimits, TheBaseCasesAreValid) {
  EXPECT_NO_THROW((void)parse_case(kCase2d, "case.toml"));
  EXPECT_NO_THROW((void)parse_case(kCase3d, "case.toml"));
}

TEST(CaseLimits, AHugeGridIsRefusedAtOnceWithAMemoryEstimate) {
  expect_invalid_case(replaced(kCase3d, "cells = [4, 4, 2]", "cells = [300, 300, 300]"),
                 {"mesh.cells", "at most 2000000 unknowns", "GB"});
  expect_invalid_case(replaced(kCase3d, "cells = [4, 4, 2]", "cells = [2000000000, 2000000000, 2000000000]"),
                 {"mesh.cells", "8e+27 nodes", "2.4e+28 unknowns"});
  expect_invalid_case(replaced(kCase2d, "cells = [29, 14]", "cells = [1000000, 1000000]"), {"mesh.cells", "GB"});
}

TEST(CaseLimits, ControlPointCountsAreBoundedAndNeverReportedWrapped) {
  // 100000² wrapped to "a list of 1410065408 numbers".
  expect_invalid_case(replaced(kCase3d, "control_points = [4, 4]", "control_points = [100000, 100000]"),
                 {"design.control_points[0] = 100000", "[2, 64]"}, {"1410065408"});
  expect_invalid_case(replaced(kCase2d, "control_points = [15]", "control_points = [1000000]"),
                 {"design.control_points[0]", "[2, 64]"});
  expect_invalid_case(replaced(kCase3d, "control_points = [4, 4]", "control_points = [40, 40]"),
                 {"design.control_points", "at most 1024 design variables", "1600"});
}

TEST(CaseLimits, PolygonSizesAreBounded) {
  expect_invalid_case(replaced(kCase3d, "mu = 0.3", "mu = 0.3\nn = 1000000"), {"contact.friction.n = 1000000", "256"});
  std::string many = "mu_vertices = [";
  for (int i = 0; i < 300; ++i) many += i ? ", 0.3" : "0.3";
  expect_invalid_case(replaced(kCase3d, "kind = \"isotropic\"\nmu = 0.3", "kind = \"polygon\"\n" + many + "]"),
                 {"contact.friction.mu_vertices", "3 to 256"});
}

TEST(CaseLimits, PhysicalBoundsNameTheField) {
  expect_invalid_case(replaced(kCase2d, "poisson = 0.3", "poisson = 0.49999999"), {"material.poisson = 0.49999999", "0.49"});
  expect_invalid_case(replaced(kCase2d, "young = 2.1e11", "young = 1e308"), {"material.young = 1e+308", "1e+13 Pa"});
  expect_invalid_case(replaced(kCase2d, "young = 2.1e11", "young = 1e-300"), {"material.young = 1e-300", "1 Pa"});
  expect_invalid_case(replaced(kCase3d, "displacement = [1.0e-4, 0.0, -1.2e-3]", "displacement = [1e300, 0.0, 0.0]"),
                 {"dirichlet[0].displacement[0]", "|displacement| <= 1 m"});
  expect_invalid_case(replaced(kCase2d, "traction = [0.0, -2.0e7]", "traction = [0.0, -1e300]"),
                 {"load[0].traction[1]", "material.young"});
  expect_invalid_case(replaced(kCase2d, "a = 2.0", "a = 1e300"), {"geometry.a", "1000000 m"});
  expect_invalid_case(replaced(kCase2d, "mu = 0.3", "mu = 1e300"), {"contact.friction.mu", "<= 10"});
}

TEST(CaseLimits, SolverSettingsThatCouldNeverBeMetAreRefused) {
  // Found by the case fuzzer (tests/fuzz): relative_tolerance = 1e-300 with a huge cap ran for hours.
  expect_invalid_case(std::string(kCase2d) + "\n[solver.qp]\nrelative_tolerance = 1e-300\n",
                 {"solver.qp.relative_tolerance = 1e-300", "1e-15 <= relative_tolerance < 1"});
  expect_invalid_case(std::string(kCase2d) + "\n[solver.qp]\nmax_iterations = 2147483647\n",
                 {"solver.qp.max_iterations = 2147483647", "<= 1000000"});
  expect_invalid_case(std::string(kCase2d) + "\n[solver.coulomb]\nmax_iterations = 100000\n",
                 {"solver.coulomb.max_iterations = 100000", "<= 10000"});
}

TEST(CaseLimits, AMeshWithoutFreeUnknownsAboveTheContactSurfaceIsRefused) {
  // One cell layer under a fully fixed top (3D [4,4,1], 2D [29,1]) left an
  // empty free block and crashed in the factorization.
  expect_invalid_case(replaced(kCase3d, "cells = [4, 4, 2]", "cells = [4, 4, 1]"),
                 {"mesh.cells = [4, 4, 1]", "no free unknown", "mesh.cells[2] >= 2"});
  const std::string top_fixed_2d = replaced(replaced(kCase2d, "face = \"left\"", "face = \"top\""),
                                            "[[load]]\nface = \"top\"\ntraction = [0.0, -2.0e7]\n", "");
  EXPECT_NO_THROW((void)parse_case(top_fixed_2d, "case.toml"));
  expect_invalid_case(replaced(top_fixed_2d, "cells = [29, 14]", "cells = [29, 1]"), {"mesh.cells = [29, 1]", "no free unknown"});
  // Without contact the bottom nodes are free: one layer is a valid body.
  const std::string no_contact = replaced(replaced(kCase3d, "cells = [4, 4, 2]", "cells = [4, 4, 1]"),
                                          "[contact]\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\n", "");
  EXPECT_NO_THROW((void)parse_case(no_contact, "case.toml"));
  // A top fixed in one component only leaves the others free.
  EXPECT_NO_THROW((void)parse_case(replaced(replaced(kCase3d, "cells = [4, 4, 2]", "cells = [4, 4, 1]"),
                                            "displacement = [1.0e-4, 0.0, -1.2e-3]",
                                            "displacement = [0.0, 0.0, -1.2e-3]\ncomponents = [2]"),
                                   "case.toml"));
}

TEST(CaseLimits, ALoadOnAComponentFixedOnTheSameFaceIsRefused) {
  const std::string text = replaced(kCase3d, "[[dirichlet]]", "[[load]]\nface = \"top\"\ntraction = [0, 0, -1e6]\n\n[[dirichlet]]");
  expect_invalid_case(text, {"load[0].traction[2] = -1000000", "dirichlet[0] fixes", "does no work"});
  // A tangential load on a top fixed only vertically is fine.
  EXPECT_NO_THROW((void)parse_case(replaced(replaced(text, "traction = [0, 0, -1e6]", "traction = [1e5, 0, 0]"),
                                            "displacement = [1.0e-4, 0.0, -1.2e-3]",
                                            "displacement = [0.0, 0.0, -1.2e-3]\ncomponents = [2]"),
                                   "case.toml"));
}

TEST(CaseLimits, OutputNamesThatCannotBeFileNamesAreRefused) {
  // A NUL byte cut "<name>.vtu" and "<name>_contact.csv" to one file.
  for (std::string_view bad : {R"("a\u0000b")", R"("")", R"("a/b")", R"("..")", R"("x\ny")"}) {
    SCOPED_TRACE(std::string(bad));
    expect_invalid_case(std::string(kCase2d) + "\n[output]\nname = " + std::string(bad) + "\n", {"output.name"});
  }
}

TEST(CaseLimits, ProblemSettingsIgnoreLayoutAndRunControls) {
  const CaseDescription a = parse_case(kCase2d, "a.toml");
  const CaseDescription b = parse_case(replaced(replaced(kCase2d, "young = 2.1e11", "young = 210000000000  # Pa"),
                                                "[contact]", "[optimization]\nmax_iterations = 7\n\n[contact]"),
                                       "b.toml");
  EXPECT_EQ(a.problem_settings, b.problem_settings);
  EXPECT_EQ(a.problem_settings.at("material.young"), "2.1e+11");
  EXPECT_EQ(a.problem_settings.at("load[0].face"), "\"top\"");
  const CaseDescription c = parse_case(replaced(kCase2d, "mu = 0.3", "mu = 0.31"), "c.toml");
  EXPECT_NE(a.problem_settings, c.problem_settings);
}

// Lists that set the amount of work (docs/case-format.md, "Size limits"): the fuzzer's cases with
// thousands of program steps, load cases or tribometer angles were accepted and ran for hours.
std::string repeated(std::string_view text, std::size_t n) {
  std::string out;
  out.reserve(text.size() * n);
  for (std::size_t k = 0; k < n; ++k) out += text;
  return out;
}

TEST(CaseLimits, LoadingProgramStepsAreBounded) {
  const std::string step = "[[program.step]]\nload_scale = [1.0]\n";
  EXPECT_NO_THROW((void)parse_case(std::string(kCase2d) + repeated(step, 3), "case.toml"));
  expect_invalid_case(std::string(kCase2d) + repeated(step, 100'001),
                      {"program.step has 100001 tables; expected at most 100000 [[program.step]] tables",
                       "Size limits"});
}

TEST(CaseLimits, LoadCasesAndTheirStepsAreBounded) {
  const std::string cost = "\n[cost]\nkind = \"compliance\"\n";
  std::string cases;
  for (int k = 0; k < 1'001; ++k) cases += "[[load_case]]\nname = \"c" + std::to_string(k) + "\"\n";
  expect_invalid_case(std::string(kCase2d) + cost + cases,
                      {"load_case has 1001 tables; expected at most 1000 [[load_case]] tables"});
  // Two cases of 60,000 steps each: within the bound of one program, beyond it together.
  const std::string steps = repeated("[[load_case.step]]\nload_scale = [1.0]\n", 60'000);
  expect_invalid_case(std::string(kCase2d) + "\n[cost]\nkind = \"dissipation\"\n" + "[[load_case]]\nname = \"a\"\n" +
                          steps + "[[load_case]]\nname = \"b\"\n" + steps,
                      {"load_case.step: the load cases have 120000 steps in all; expected at most 100000"});
}

TEST(CaseLimits, TribometerAnglesAndRampSolvesAreBounded) {
  const auto experiment = [](const std::string& angles, int ramp_steps) {
    return kCase3d + "\n[experiment]\nnormal_force = 1.0e4\npull_displacement = 1.0e-5\nramp_steps = " +
           std::to_string(ramp_steps) + "\nangles_degrees = [" + angles + "]\n";
  };
  EXPECT_NO_THROW((void)parse_case(experiment("0, 90", 20), "case.toml"));
  std::string many = "0";
  for (int k = 1; k < 10'001; ++k) many += ", " + std::to_string(k % 360);
  expect_invalid_case(experiment(many, 1),
                      {"experiment.angles_degrees has 10001 angles; expected at most 10000 pull directions"});
  std::string hundred = "0";
  for (int k = 1; k < 100; ++k) hundred += ", " + std::to_string(k);
  expect_invalid_case(experiment(hundred, 100'000),
                      {"experiment.angles_degrees has 100 angles with ramp_steps = 100000: 10000000 ramp solves; "
                       "expected at most 1000000"});
}

TEST(CaseLimits, BodyTablesAreBounded) {
  const std::string load = "[[load]]\nface = \"top\"\ntraction = [0.0, -1.0]\n";
  expect_invalid_case(std::string(kCase2d) + repeated(load, 1'000),
                      {"load has 1001 tables; expected at most 1000 [[load]] tables"});
  const std::string force = "[[force]]\nboundary = \"top\"\nforce = [0.0, -1.0]\n";
  expect_invalid_case(std::string(kCase2d) + repeated(force, 1'001),
                      {"force has 1001 tables; expected at most 1000 [[force]] tables"});
  const std::string constraint = "[[constraint]]\nat = [0.0, 1.0]\ntolerance = 0.1\n";
  expect_invalid_case(std::string(kCase2d) + repeated(constraint, 1'001),
                      {"constraint has 1001 tables; expected at most 1000 [[constraint]] tables"});
}

class CaseFiles : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(CaseFiles, AnEmptyCaseFileIsReportedAsEmpty) {
  const auto path = dir_ / "empty.toml";
  std::ofstream(path).close();
  try {
    (void)load_case(path);
    FAIL() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("is empty"), std::string::npos) << e.what();
  }
}

TEST_F(CaseFiles, AByteOrderMarkIsSkippedInCaseFilesAndMeasurementCsvs) {
  const auto case_path = dir_ / "bom.toml";
  std::ofstream(case_path, std::ios::binary) << "\xEF\xBB\xBF" << kCase2d;
  EXPECT_NO_THROW((void)load_case(case_path));
  const auto csv = dir_ / "bom.csv";
  std::ofstream(csv, std::ios::binary) << "\xEF\xBB\xBF" << "quantity,location,value,sigma\ntotal_normal_force,all,1.0,0.1\n";
  const auto rows = read_measurements(csv);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].value, 1.0);
}

TEST_F(CaseFiles, AMeasurementFileIsBoundedInRows) {
  const auto csv = dir_ / "many.csv";
  {
    std::ofstream out(csv);
    out << "quantity,location,value,sigma\n";
    for (int k = 0; k < 100'001; ++k) out << "normal_force,0,1.0,0.1\n";
  }
  try {
    (void)read_measurements(csv);
    FAIL() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("many.csv:100002: measurement 100001; expected at most 100000 measurements"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace frictopt::io
