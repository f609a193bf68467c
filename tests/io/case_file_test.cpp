// SPDX-License-Identifier: MIT
// Case-file parsing: valid 2D and 3D cases give the expected values; every kind of bad input
// (syntax, unknown key, wrong type, missing field, out of range, size not matching the
// dimension) gives an InvalidInput whose message names the field.
#include "common/invalid_case.hpp"
#include "frictopt/io/case_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/face.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace frictopt::io {
namespace {

using testing::expect_invalid_case;
using testing::replaced;

using contact::FrictionLawKind;
using cost::CostKind;
using fem::PlaneModel;
using mesh::Face;
using shape::SlopeScaling;

// The thesis' 2D example (docs/theory/problem.md §6, docs/theory/examples.md §1): a = 2, C4 = 1,
// d = 15, C2 = 1.9.
constexpr std::string_view kValid2d = R"(
[geometry]
dim = 2
a = 2.0
height = 1.0

[mesh]
cells = [29, 14]
grading = 2.0

[material]
young = 2.1e11
poisson = 0.3

[[load]]
face = "top"
traction = [0.0, -2.0e7]

[[dirichlet]]
face = "left"

[[dirichlet]]
face = "right"
displacement = [0.0, 1e-3]
components = [1]

[design]
control_points = [15]
initial = 0.05
upper_bound = 0.75
slope_bound = 1.0
volume = 1.9

[contact]
[contact.friction]
kind = "isotropic"
mu = 0.3

[solver.coulomb]
max_iterations = 40
relative_tolerance = 1e-9

[output]
every = 5
)";

constexpr std::string_view kValid3d = R"(
[geometry]
dim = 3
a = 2
b = 1
height = 1

[mesh]
cells = [20, 10, 8]

[material]
young = 1e9
poisson = 0.25

[[load]]
face = "top"
traction = [1e5, 0, -1e6]

[[load]]
face = "front"
traction = [0, 2e5, 0]

[[dirichlet]]
face = "left"
components = [2, 0]

[design]
control_points = [4, 3]
initial = [0.0, 0.1, 0.1, 0.0, 0.1, 0.2, 0.2, 0.1, 0.0, 0.1, 0.1, 0.0]
upper_bound = 0.5
slope_scaling = "exact"

[contact]
law = "coulomb"
[contact.friction]
kind = "polygon"
mu_vertices = [0.3, 0.2, 0.3, 0.2]

[solver.qp]
max_iterations = 500

[solver.fem]

[output]
vtk = false
name = "block"
)";



TEST(ParseCase, Valid2dCaseGivesTheWrittenValuesAndDefaults) {
  const CaseDescription c = parse_case(kValid2d, "cases2d/thesis/case.toml");
  const study::BodyDefinition& body = c.body;
  EXPECT_EQ(c.origin, "cases2d/thesis/case.toml");
  EXPECT_EQ(c.dim(), 2);
  EXPECT_EQ(body.shape.extents()[0], 2.0);
  EXPECT_EQ(body.height, 1.0);
  EXPECT_EQ(body.resolution.cells, (std::array<int, 3>{29, 0, 14})) << "(n1, unused n2, n_vertical) in 2D";
  EXPECT_EQ(body.resolution.grading, 2.0);
  EXPECT_EQ(body.material.young, 2.1e11);
  EXPECT_EQ(body.material.poisson, 0.3);
  EXPECT_EQ(body.material.plane_model, PlaneModel::kPlaneStrain);
  ASSERT_EQ(body.tractions.size(), 1u);
  EXPECT_EQ(body.tractions[0].boundary, "top");
  EXPECT_EQ(body.tractions[0].traction, Eigen::Vector2d(0.0, -2.0e7));
  ASSERT_EQ(body.dirichlet.size(), 2u);
  EXPECT_EQ(body.dirichlet[0].boundary, "left");
  EXPECT_EQ(body.dirichlet[0].displacement, Eigen::Vector2d::Zero());
  EXPECT_EQ(body.dirichlet[0].components, (std::vector<int>{0, 1}));
  EXPECT_EQ(body.dirichlet[1].boundary, "right");
  EXPECT_EQ(body.dirichlet[1].displacement, Eigen::Vector2d(0.0, 1e-3));
  EXPECT_EQ(body.dirichlet[1].components, (std::vector<int>{1}));
  EXPECT_EQ(body.shape.num_controls(), 15);
  EXPECT_EQ(body.initial_design, Eigen::VectorXd::Constant(15, 0.05));
  EXPECT_EQ(body.admissible.upper_bound, 0.75);
  EXPECT_EQ(body.admissible.height, 1.0);
  EXPECT_EQ(body.admissible.slope_bound, 1.0);
  EXPECT_EQ(body.admissible.volume, 1.9);
  EXPECT_EQ(body.admissible.slope_scaling, SlopeScaling::kThesis);
  ASSERT_TRUE(body.contact.has_value());
  EXPECT_EQ(body.contact->law.kind(), FrictionLawKind::kInterval) << "2D friction sets are intervals";
  EXPECT_EQ(body.contact->law.vertices()[0], Eigen::Vector2d(-0.3, 0.0));
  EXPECT_EQ(body.contact->law.vertices()[1], Eigen::Vector2d(0.3, 0.0));
  const contact::CoulombSolver::Options defaults;
  EXPECT_EQ(body.contact->coulomb.max_iterations, 40);
  EXPECT_EQ(body.contact->coulomb.relative_tolerance, 1e-9);
  EXPECT_EQ(body.contact->coulomb.tresca.max_iterations, defaults.tresca.max_iterations);
  EXPECT_EQ(body.contact->coulomb.tresca.relative_tolerance, defaults.tresca.relative_tolerance);
  EXPECT_TRUE(c.output.vtk);
  EXPECT_EQ(c.output.every, 5);
  EXPECT_EQ(c.output.name, "thesis") << "default name: the case directory for <dir>/case.toml";
  EXPECT_EQ(body.name, c.output.name);
}

TEST(ParseCase, Valid3dCaseGivesTheWrittenValuesAndDefaults) {
  const CaseDescription c = parse_case(kValid3d, "block.toml");
  const study::BodyDefinition& body = c.body;
  EXPECT_EQ(c.dim(), 3);
  EXPECT_EQ(body.shape.extents()[0], 2.0) << "integers are valid numbers";
  EXPECT_EQ(body.shape.extents()[1], 1.0);
  EXPECT_EQ(body.resolution.cells, (std::array<int, 3>{20, 10, 8}));
  EXPECT_EQ(body.resolution.grading, 1.0);
  ASSERT_EQ(body.tractions.size(), 2u);
  EXPECT_EQ(body.tractions[0].traction, Eigen::Vector3d(1e5, 0, -1e6));
  EXPECT_EQ(body.tractions[1].boundary, "front");
  ASSERT_EQ(body.dirichlet.size(), 1u);
  EXPECT_EQ(body.dirichlet[0].components, (std::vector<int>{0, 2})) << "components are sorted";
  EXPECT_EQ(body.dirichlet[0].displacement, Eigen::Vector3d::Zero());
  EXPECT_EQ(body.shape.num_controls(), 12);
  EXPECT_EQ(body.initial_design.size(), 12);
  EXPECT_EQ(body.initial_design[5], 0.2);
  EXPECT_FALSE(body.admissible.slope_bound.has_value());
  EXPECT_FALSE(body.admissible.volume.has_value());
  EXPECT_EQ(body.admissible.slope_scaling, SlopeScaling::kExact);
  ASSERT_TRUE(body.contact.has_value());
  const contact::FrictionLaw expected = contact::FrictionLaw::polygon({0.3, 0.2, 0.3, 0.2});
  EXPECT_EQ(body.contact->law.kind(), FrictionLawKind::kPolygon);
  EXPECT_EQ(body.contact->law.describe(), expected.describe());
  ASSERT_EQ(body.contact->law.vertices().size(), 4u) << "n defaults to the number of vertex coefficients";
  const contact::CoulombSolver::Options defaults;
  EXPECT_EQ(body.contact->coulomb.tresca.max_iterations, 500);
  EXPECT_EQ(body.contact->coulomb.max_iterations, defaults.max_iterations);
  EXPECT_FALSE(c.output.vtk);
  EXPECT_EQ(c.output.every, 1);
  EXPECT_EQ(c.output.name, "block");
  // No [optimization]: the study's defaults.
  const optim::BundleTrust::Options study_defaults = study::default_study_options(body);
  EXPECT_EQ(c.optimization.max_iterations, study_defaults.max_iterations);
  EXPECT_EQ(c.optimization.max_step_length, body.admissible.upper_bound);
}

TEST(ParseCase, AbsentContactTableMeansNoContact) {
  const std::string text =
      replaced(kValid2d, "[contact]\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\n", "");
  EXPECT_FALSE(parse_case(text, "case.toml").body.contact.has_value());
}

TEST(ParseCase, ContactWithoutFrictionTableIsFrictionless) {
  const std::string text =
      replaced(kValid2d, "[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\n", "");
  const CaseDescription c = parse_case(text, "case.toml");
  ASSERT_TRUE(c.body.contact.has_value());
  EXPECT_TRUE(c.body.contact->law.is_zero());
}

TEST(ParseCase, IsotropicAndEllipticLawsIn3dDefaultToSixteenSides) {
  const std::string iso =
      replaced(kValid3d, "kind = \"polygon\"\nmu_vertices = [0.3, 0.2, 0.3, 0.2]",
               "kind = \"isotropic\"\nmu = 0.5");
  const contact::FrictionLaw iso_law = parse_case(iso, "case.toml").body.contact->law;
  EXPECT_EQ(iso_law.kind(), FrictionLawKind::kRegularPolygon);
  EXPECT_EQ(iso_law.vertices().size(), 16u);
  const std::string ellipse =
      replaced(kValid3d, "kind = \"polygon\"\nmu_vertices = [0.3, 0.2, 0.3, 0.2]",
               "kind = \"ellipse\"\nmu_x = 0.4\nmu_y = 0.2\nn = 32");
  const contact::FrictionLaw f = parse_case(ellipse, "case.toml").body.contact->law;
  EXPECT_EQ(f.kind(), FrictionLawKind::kEllipsePolygon);
  EXPECT_EQ(f.semi_axes(), Eigen::Vector2d(0.4, 0.2));
  EXPECT_EQ(f.vertices().size(), 32u);
}

TEST(ParseCase, DirectionDependentFrictionIn2dReadsBothCoefficients) {
  const std::string text = replaced(kValid2d, "kind = \"isotropic\"\nmu = 0.3",
                                    "kind = \"polygon\"\nmu_plus = 0.4\nmu_minus = 0.1");
  const contact::FrictionLaw f = parse_case(text, "case.toml").body.contact->law;
  EXPECT_EQ(f.kind(), FrictionLawKind::kInterval);
  EXPECT_EQ(f.support(1.0), 0.4) << "slip in +x1 costs mu_plus";
  EXPECT_EQ(f.support(-1.0), 0.1) << "slip in -x1 costs mu_minus";
}

TEST(ParseCase, PlaneStressIsAccepted) {
  const std::string text =
      replaced(kValid2d, "poisson = 0.3", "poisson = 0.3\nmodel = \"plane_stress\"");
  EXPECT_EQ(parse_case(text, "case.toml").body.material.plane_model, PlaneModel::kPlaneStress);
}

TEST(ParseCase, SyntaxErrorNamesTheLine) {
  expect_invalid_case(replaced(kValid2d, "a = 2.0", "a = = 2.0"), {"case.toml:4:", "TOML syntax"});
}

TEST(ParseCase, UnknownKeyIsNamedWithTheAcceptedKeysAndASuggestion) {
  expect_invalid_case(replaced(kValid2d, "height = 1.0", "heigth = 1.0"),
                 {"case.toml:5:", "unknown key 'geometry.heigth'", "did you mean 'height'",
                  "expected one of dim, a, b, height"});
}

TEST(ParseCase, UnknownTopLevelTableIsAnError) {
  expect_invalid_case(std::string(kValid2d) + "\n[meshh]\ncells = [1, 1]\n",
                 {"unknown key 'meshh'", "did you mean 'mesh'"});
}

TEST(ParseCase, CostAndOptimizationTablesAreValidated) {
  const CaseDescription c = parse_case(std::string(kValid2d) +
                                           "\n[cost]\nkind = \"target_pressure\"\ntarget = \"initial_mean\"\n"
                                           "[optimization]\nmax_iterations = 30\nepsilon = 1e-5\n",
                                       "case.toml");
  ASSERT_TRUE(c.cost.has_value());
  EXPECT_EQ(c.cost->kind, CostKind::kTargetPressure);
  EXPECT_TRUE(std::isnan(c.cost->target_pressure)) << "NaN: the initial mean pressure";
  EXPECT_EQ(c.optimization.max_iterations, 30);
  EXPECT_EQ(c.optimization.epsilon, 1e-5);
  EXPECT_FALSE(c.optimization.variable_metric) << "opt-in";
  const CaseDescription metric =
      parse_case(std::string(kValid2d) + "\n[optimization]\nvariable_metric = true\n", "case.toml");
  EXPECT_TRUE(metric.optimization.variable_metric);
  expect_invalid_case(std::string(kValid2d) + "\n[optimization]\nvariable_metric = 1\n",
                      {"optimization.variable_metric"});
  EXPECT_TRUE(c.optimization.use_piece_cuts) << "the other load cases' cuts are on by default";
  const CaseDescription no_cuts =
      parse_case(std::string(kValid2d) + "\n[optimization]\ncase_cuts = false\n", "case.toml");
  EXPECT_FALSE(no_cuts.optimization.use_piece_cuts);
  expect_invalid_case(std::string(kValid2d) + "\n[optimization]\ncase_cuts = \"no\"\n",
                      {"optimization.case_cuts"});
  // The confirmation in the point's units is on by default (docs/optim.md, "Confirmation in the
  // point's units"); a case can switch it off or move its threshold, never below 1.
  EXPECT_TRUE(c.optimization.confirm_in_point_units);
  EXPECT_EQ(c.optimization.point_units_spread, 10.0);
  const CaseDescription units = parse_case(
      std::string(kValid2d) + "\n[optimization]\nconfirm_in_point_units = false\npoint_units_spread = 100\n",
      "case.toml");
  EXPECT_FALSE(units.optimization.confirm_in_point_units);
  EXPECT_EQ(units.optimization.point_units_spread, 100.0);
  expect_invalid_case(std::string(kValid2d) + "\n[optimization]\npoint_units_spread = 0.5\n",
                      {"optimization.point_units_spread", "0.5"});
  expect_invalid_case(std::string(kValid2d) + "\n[optimization]\nconfirm_in_point_units = \"yes\"\n",
                      {"optimization.confirm_in_point_units"});
  expect_invalid_case(std::string(kValid2d) + "\n[cost]\nkind = \"x\"\n", {"cost.kind"});
  expect_invalid_case(std::string(kValid2d) + "\n[cost]\nkind = \"target_pressure\"\n", {"cost.target"});
  expect_invalid_case(std::string(kValid2d) + "\n[cost]\nkind = \"compliance\"\nexponent = 4\n", {"cost.exponent"});
  expect_invalid_case(std::string(kValid2d) + "\n[optimization]\nbundle_size = 2\n", {"optimization.bundle_size"});
  expect_invalid_case(std::string(kValid2d) + "\n[optimization]\nmax_iters = 2\n", {"optimization.max_iters"});
  // [study] combines load cases: alone it is an error naming the missing tables.
  expect_invalid_case(std::string(kValid2d) + "\n[study]\n", {"load_case", "is missing"});
}

TEST(ParseCase, TractionUniformityTakesTheMeanOrATargetOfDimMinusOneComponents) {
  const CaseDescription mean =
      parse_case(std::string(kValid3d) + "\n[cost]\nkind = \"traction_uniformity\"\n", "case.toml");
  ASSERT_TRUE(mean.cost.has_value());
  EXPECT_EQ(mean.cost->kind, CostKind::kTractionUniformity);
  EXPECT_EQ(mean.cost->target_traction.size(), 0);
  const CaseDescription target = parse_case(
      std::string(kValid3d) + "\n[cost]\nkind = \"traction_uniformity\"\ntarget = [2e4, -1e4]\n", "case.toml");
  EXPECT_EQ(target.cost->target_traction, Eigen::Vector2d(2e4, -1e4));
  EXPECT_TRUE(parse_case(std::string(kValid2d) + "\n[cost]\nkind = \"traction_uniformity\"\ntarget = \"mean\"\n",
                         "case.toml")
                  .cost->target_traction.size() == 0);
  expect_invalid_case(std::string(kValid2d) + "\n[cost]\nkind = \"traction_uniformity\"\ntarget = [1, 2]\n",
                 {"cost.target has 2 components; expected 1"});
  expect_invalid_case(std::string(kValid3d) + "\n[cost]\nkind = \"traction_uniformity\"\ntarget = \"median\"\n",
                 {"cost.target", "\"mean\"", "\"initial_mean\""});
  EXPECT_TRUE(parse_case(std::string(kValid3d) + "\n[cost]\nkind = \"traction_uniformity\"\ntarget = \"initial_mean\"\n",
                         "case.toml")
                  .cost->target_traction_initial_mean);
}

TEST(ParseCase, UnknownKeyInNestedTablesIsNamedWithItsPath) {
  expect_invalid_case(replaced(kValid2d, "mu = 0.3", "mu = 0.3\nmuu = 0.1"), {"contact.friction.muu"});
  expect_invalid_case(replaced(kValid2d, "max_iterations = 40", "max_iter = 40"),
                 {"solver.coulomb.max_iter"});
  expect_invalid_case(replaced(kValid3d, "[solver.fem]", "[solver.fem]\nordering = \"amd\""),
                 {"solver.fem.ordering"});
  expect_invalid_case(replaced(kValid2d, "face = \"left\"", "face = \"left\"\nvalue = 0"),
                 {"dirichlet[0].value"});
}

TEST(ParseCase, WrongTypeNamesFieldValueAndExpectedType) {
  expect_invalid_case(replaced(kValid2d, "a = 2.0", "a = \"2.0\""),
                 {"geometry.a = \"2.0\" (a string); expected a number"});
  expect_invalid_case(replaced(kValid2d, "dim = 2", "dim = 2.0"),
                 {"geometry.dim = 2 (a float); expected an integer"});
  expect_invalid_case(replaced(kValid2d, "cells = [29, 14]", "cells = [29, 14.5]"),
                 {"mesh.cells[1] = 14.5 (a float); expected an integer"});
  expect_invalid_case(replaced(kValid2d, "every = 5", "every = 5\nvtk = \"yes\""), {"output.vtk"});
  expect_invalid_case(replaced(kValid2d, "[mesh]\ncells", "mesh = 3\n[mesh2]\ncells"), {"mesh"});
}

TEST(ParseCase, NonFiniteNumbersAreRejected) {
  expect_invalid_case(replaced(kValid2d, "young = 2.1e11", "young = inf"),
                 {"material.young = inf; expected a finite number"});
  expect_invalid_case(replaced(kValid2d, "poisson = 0.3", "poisson = nan"), {"material.poisson"});
}

TEST(ParseCase, MissingRequiredFieldsAreNamed) {
  expect_invalid_case(replaced(kValid2d, "height = 1.0", ""),
                 {"geometry.height is missing", "expected a number > 0"});
  expect_invalid_case(replaced(kValid2d, "young = 2.1e11", ""), {"material.young is missing"});
  expect_invalid_case(replaced(kValid2d, "initial = 0.05", ""), {"design.initial is missing"});
  expect_invalid_case(replaced(kValid2d, "[material]\nyoung = 2.1e11\npoisson = 0.3\n", ""),
                 {"material is missing", "a table [material]"});
  expect_invalid_case(replaced(kValid2d, "face = \"top\"\n", ""), {"load[0].face is missing"});
  expect_invalid_case(replaced(kValid2d, "kind = \"isotropic\"\nmu = 0.3", "kind = \"isotropic\""),
                 {"contact.friction.mu is missing"});
  expect_invalid_case(replaced(kValid3d, "b = 1\n", ""), {"geometry.b is missing", "in 3D"});
}

// Without [contact]; with it the body floats, held by contact and friction (docs/experiments.md §5;
// the floating-body tests of tests/study/floating_body_test.cpp and tests/cli/experiment_test.cpp).
TEST(ParseCase, AtLeastOneDirichletConditionIsRequired) {
  const std::string text = replaced(
      replaced(replaced(kValid2d, "[[dirichlet]]\nface = \"left\"\n", ""),
               "[[dirichlet]]\nface = \"right\"\ndisplacement = [0.0, 1e-3]\ncomponents = [1]\n", ""),
      "[contact]\n[contact.friction]\nkind = \"isotropic\"\nmu = 0.3\n", "");
  expect_invalid_case(text, {"dirichlet is missing", "rigid-body modes"});
}

TEST(ParseCase, OutOfRangeValuesNameFieldValueAndRange) {
  expect_invalid_case(replaced(kValid2d, "poisson = 0.3", "poisson = 0.6"),
                 {"case.toml:13: material.poisson = 0.6; expected 0 <= poisson < 0.5"});
  expect_invalid_case(replaced(kValid2d, "young = 2.1e11", "young = -1"),
                 {"material.young = -1; expected young > 0"});
  expect_invalid_case(replaced(kValid2d, "dim = 2", "dim = 4"), {"geometry.dim = 4; expected 2 or 3"});
  expect_invalid_case(replaced(kValid2d, "a = 2.0", "a = 0.0"), {"geometry.a = 0; expected 1e-06 <= a <= 1000000 m"});
  expect_invalid_case(replaced(kValid2d, "grading = 2.0", "grading = 0.5"),
                 {"mesh.grading = 0.5", "1 <= grading <= 10"});
  expect_invalid_case(replaced(kValid2d, "cells = [29, 14]", "cells = [29, 0]"),
                 {"mesh.cells[1] = 0; expected an integer >= 1"});
  expect_invalid_case(replaced(kValid2d, "control_points = [15]", "control_points = [1]"),
                 {"design.control_points[0] = 1; expected an integer in [2, 64]"});
  expect_invalid_case(replaced(kValid2d, "initial = 0.05", "initial = 0.8"),
                 {"design.initial = 0.8; expected 0 <= α <= upper_bound = 0.75"});
  expect_invalid_case(replaced(kValid2d, "upper_bound = 0.75", "upper_bound = 1.0"),
                 {"design.upper_bound = 1", "< geometry.height = 1"});
  expect_invalid_case(replaced(kValid2d, "slope_bound = 1.0", "slope_bound = 0"),
                 {"design.slope_bound = 0; expected slope_bound > 0"});
  expect_invalid_case(replaced(kValid2d, "max_iterations = 40", "max_iterations = 0"),
                 {"solver.coulomb.max_iterations = 0; expected 1 <= max_iterations <= 10000"});
  expect_invalid_case(replaced(kValid2d, "relative_tolerance = 1e-9", "relative_tolerance = -1e-9"),
                 {"solver.coulomb.relative_tolerance = -1e-09"});
  expect_invalid_case(replaced(kValid2d, "every = 5", "every = 0"), {"output.every = 0"});
  expect_invalid_case(replaced(kValid3d, "name = \"block\"", "name = \"a/b\""), {"output.name"});
}

TEST(ParseCase, UnreachableVolumeIsRejectedWithTheReachableInterval) {
  // The thesis' printed formula reads C2 as d·(mean height); as an area, 28.5 is far outside
  // [a·(C4 − C0), a·C4] = [0.5, 2] (docs/theory/problem.md §6).
  expect_invalid_case(replaced(kValid2d, "volume = 1.9", "volume = 28.5"),
                 {"design.volume = 28.5; expected 0.5 <= volume <= 2"});
}

TEST(ParseCase, SizesMustMatchTheDimension) {
  expect_invalid_case(replaced(kValid2d, "cells = [29, 14]", "cells = [29, 3, 14]"),
                 {"mesh.cells = [29, 3, 14]; expected a list of 2 integers"});
  expect_invalid_case(replaced(kValid3d, "cells = [20, 10, 8]", "cells = [20, 8]"),
                 {"mesh.cells", "a list of 3 integers"});
  expect_invalid_case(replaced(kValid2d, "traction = [0.0, -2.0e7]", "traction = [0.0, 0.0, -2.0e7]"),
                 {"load[0].traction = [0, 0, -20000000]; expected a list of 2 numbers"});
  expect_invalid_case(replaced(kValid3d, "traction = [1e5, 0, -1e6]", "traction = [1e5, -1e6]"),
                 {"load[0].traction", "3 numbers"});
  expect_invalid_case(replaced(kValid2d, "displacement = [0.0, 1e-3]", "displacement = [1e-3]"),
                 {"dirichlet[1].displacement"});
  expect_invalid_case(replaced(kValid2d, "components = [1]", "components = [2]"),
                 {"dirichlet[1].components[0] = 2; expected an index in 0..1"});
  expect_invalid_case(replaced(kValid2d, "control_points = [15]", "control_points = [15, 3]"),
                 {"design.control_points", "a list [m1]"});
  expect_invalid_case(replaced(kValid3d, "initial = [0.0, 0.1, 0.1, 0.0,", "initial = [0.1, 0.0,"),
                 {"design.initial", "a list of 12 numbers"});
  expect_invalid_case(replaced(kValid2d, "a = 2.0", "a = 2.0\nb = 1.0"),
                 {"geometry.b = 1 is only allowed in 3D"});
  expect_invalid_case(replaced(kValid3d, "poisson = 0.25", "poisson = 0.25\nmodel = \"plane_strain\""),
                 {"material.model", "only allowed in 2D"});
}

TEST(ParseCase, FacesAreCheckedAgainstTheDimension) {
  expect_invalid_case(replaced(kValid2d, "face = \"top\"", "face = \"front\""),
                 {"load[0].face = \"front\"; expected one of left, right, top in 2D"});
  expect_invalid_case(replaced(kValid2d, "face = \"top\"", "face = \"bottom\""),
                 {"load[0].face = \"bottom\"", "contact surface"});
  expect_invalid_case(replaced(kValid3d, "face = \"left\"", "face = \"side\""),
                 {"dirichlet[0].face = \"side\"", "left, right, front, back, top"});
}

TEST(ParseCase, AComponentFixedTwiceOnOneFaceIsAnError) {
  expect_invalid_case(replaced(kValid2d, "face = \"right\"", "face = \"left\""),
                 {"dirichlet[1].face = \"left\" fixes component 1", "dirichlet[0]"});
}

TEST(ParseCase, FrictionLawsAreValidated) {
  const std::string_view poly = "mu_vertices = [0.3, 0.2, 0.3, 0.2]";
  expect_invalid_case(replaced(kValid3d, poly, "mu_vertices = [0.3, -0.2, 0.3, 0.2]"),
                 {"contact.friction.mu_vertices[1] = -0.2", "0 <= mu_vertices[i] <= 10"});
  expect_invalid_case(replaced(kValid3d, poly, "mu_vertices = [0.3, 0.2]"),
                 {"contact.friction.mu_vertices = [0.3, 0.2]", "3 to 256 numbers"});
  expect_invalid_case(replaced(kValid3d, poly, "mu_vertices = [0.3, 0.2, 0.3, 0.2]\nn = 6"),
                 {"contact.friction.n = 6", "length of mu_vertices (4)"});
  expect_invalid_case(replaced(kValid3d, "kind = \"polygon\"\n" + std::string(poly),
                          "kind = \"isotropic\"\nmu = 0.3\nn = 2"),
                 {"contact.friction.n = 2; expected 3 <= n <= 256"});
  expect_invalid_case(replaced(kValid2d, "mu = 0.3", "mu = -0.3"),
                 {"contact.friction.mu = -0.3; expected 0 <= mu <= 10"});
  expect_invalid_case(replaced(kValid2d, "kind = \"isotropic\"", "kind = \"ellipse\""),
                 {"contact.friction.kind = \"ellipse\"", "none, isotropic, polygon in 2D"});
  expect_invalid_case(replaced(kValid2d, "kind = \"isotropic\"", "kind = \"anisotropic\""),
                 {"contact.friction.kind = \"anisotropic\""});
  expect_invalid_case(replaced(kValid2d, "mu = 0.3", "mu = 0.3\nn = 8"),
                 {"contact.friction.n = 8 is not used by kind = \"isotropic\" in 2D"});
  expect_invalid_case(replaced(kValid3d, poly, std::string(poly) + "\nmu = 0.3"),
                 {"contact.friction.mu = 0.3 is not used by kind = \"polygon\""});
  expect_invalid_case(
      replaced(kValid2d, "kind = \"isotropic\"\nmu = 0.3", "kind = \"polygon\"\nmu_plus = 0.3"),
      {"contact.friction.mu_minus is missing"});
  expect_invalid_case(replaced(kValid3d, "law = \"coulomb\"", "law = \"tresca\""),
                 {"contact.law = \"tresca\"; expected one of coulomb"});
}

TEST(LoadCase, ReadsAFileAndUsesItsPathInMessages) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("frictopt_io_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "plate.toml";
  {
    std::ofstream out(file);
    out << kValid2d;
  }
  const CaseDescription c = load_case(file);
  EXPECT_EQ(c.output.name, "plate");
  EXPECT_EQ(c.origin, file.string());
  {
    std::ofstream out(file);
    out << replaced(kValid2d, "poisson = 0.3", "poisson = 0.5");
  }
  try {
    (void)load_case(file);
    ADD_FAILURE() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ":13: material.poisson = 0.5"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(LoadCase, MissingFileIsInvalidInputNamingThePath) {
  EXPECT_THROW((void)load_case("/nonexistent/frictopt/case.toml"), InvalidInput);
}

TEST(CaseEnums, SpellingsComeFromTheNumericModulesTables) {
  for (Face f : {Face::kLeft, Face::kRight, Face::kFront, Face::kBack, Face::kTop})
    EXPECT_EQ(mesh::parse_face(mesh::to_string(f)), f);
  for (CostKind k : {CostKind::kTargetPressure, CostKind::kNormalForcePower, CostKind::kCompliance,
                     CostKind::kPressureNorm, CostKind::kTotalSlip, CostKind::kTractionUniformity})
    EXPECT_EQ(cost::parse_cost_kind(cost::to_string(k)), k);
  EXPECT_EQ(fem::parse_plane_model("plane_stress"), PlaneModel::kPlaneStress);
  EXPECT_EQ(shape::kSlopeScalingNames.find("exact"), SlopeScaling::kExact);
  EXPECT_THROW((void)cost::parse_cost_kind("compliancee"), InvalidInput);
}

TEST(ParseCase, PressureNormDefaultsToExponentEightAndForcePowerToFour) {
  EXPECT_EQ(parse_case(std::string(kValid2d) + "\n[cost]\nkind = \"pressure_norm\"\n", "case.toml").cost->exponent, 8.0);
  EXPECT_EQ(parse_case(std::string(kValid2d) + "\n[cost]\nkind = \"normal_force_power\"\n", "case.toml").cost->exponent,
            4.0);
}

}  // namespace
}  // namespace frictopt::io
