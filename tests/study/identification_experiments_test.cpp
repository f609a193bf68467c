// SPDX-License-Identifier: MIT
// Several experiments in one identification and inline measurements (docs/identification.md,
// "Several experiments", "Inline measurements"): an experiment is the case with its loads scaled
// and its law turned (values and Jacobian rows against single-experiment models of those cases);
// cases3d/identify-lay, where each tribometer experiment alone leaves one coefficient undetermined
// and the joint fit recovers both; the case-file tables and their errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "common/case_text.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/measurements.hpp"
#include "frictopt/study/identification.hpp"

namespace frictopt::study {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

// A 3D block pressed by a rigid plate that also moves sideways (thesis-style 3 × 3 dish, as in
// identification_test.cpp's block), with the anisotropic 16-gon on the ellipse (0.25, 0.4).
BodyDefinition block(const contact::FrictionLaw& law, Eigen::Vector3d plate = Eigen::Vector3d(6e-5, -2e-5, -1.2e-3)) {
  BodyDefinition b;
  b.shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  b.height = 0.5;
  b.resolution = {{5, 5, 3}, 1.0};
  b.material = {7e10, 0.33, fem::PlaneModel::kPlaneStrain};
  b.dirichlet = {{"top", {}, plate}};
  b.tractions = {{"right", Eigen::Vector3d(2e6, 1e6, 0.0)}};
  b.admissible.upper_bound = 5e-3;
  b.admissible.height = 0.5;
  b.initial_design.resize(9);
  b.initial_design << 0.6e-3, 0.5e-3, 0.6e-3, 0.5e-3, 0.2e-3, 0.5e-3, 0.6e-3, 0.5e-3, 0.6e-3;
  ContactDefinition c;
  c.law = law;
  b.contact = c;
  return b;
}

const contact::FrictionLaw kLaw = contact::FrictionLaw::ellipse_polygon(0.25, 0.4, 16);

// Forces at every contact node and the totals (σ = 1: only values and Jacobians are compared).
std::vector<Measurement> sensors(int num_nodes) {
  std::vector<Measurement> out;
  for (int i = 0; i < num_nodes; ++i)
    for (MeasuredQuantity q : {MeasuredQuantity::kNormalForce, MeasuredQuantity::kTangentialForceX1,
                               MeasuredQuantity::kTangentialForceX2}) {
      Measurement m;
      m.quantity = q;
      m.node = i;
      out.push_back(m);
    }
  for (MeasuredQuantity q : {MeasuredQuantity::kTotalNormalForce, MeasuredQuantity::kTotalTangentialForceX1}) {
    Measurement m;
    m.quantity = q;
    out.push_back(m);
  }
  return out;
}

Identification::Options ellipse_options(bool young = false) {
  Identification::Options o;
  o.parameters = {{"mu_x", kNaN, 0.02, 1.5}, {"mu_y", kNaN, 0.02, 1.5}};
  if (young) o.parameters.push_back({"young", kNaN, 1e10, 3e11});
  return o;
}

// Experiment e's rows of a joint model equal a single-experiment model of the case with e's loads
// and law written into it: the scales multiply the right tables, the turn is the law's rotated(),
// and the rows and Jacobian blocks are stacked in order.
TEST(IdentificationExperiments, EachExperimentIsTheCaseWithItsLoadsAndTurnedLaw) {
  const int p = 36;  // 6 × 6 contact nodes
  IdentificationExperiment plain;
  plain.name = "plain";
  plain.measurements = sensors(p);
  IdentificationExperiment turned;
  turned.name = "turned";
  turned.orientation = 30.0 * std::numbers::pi / 180.0;
  turned.dirichlet_scale = {0.8};
  turned.load_scale = {1.5};
  turned.measurements = sensors(p);
  Identification joint(block(kLaw), {plain, turned}, ellipse_options(true));
  ASSERT_EQ(joint.experiment_names(), (std::vector<std::string>{"plain", "turned"}));
  ASSERT_EQ(joint.measurements().size(), 2u * plain.measurements.size());
  EXPECT_EQ(joint.measurement_experiment().front(), 0);
  EXPECT_EQ(joint.measurement_experiment().back(), 1);

  BodyDefinition written = block(kLaw.rotated(30.0 * std::numbers::pi / 180.0), Eigen::Vector3d(0.8 * 6e-5, 0.8 * -2e-5, 0.8 * -1.2e-3));
  written.tractions[0].traction *= 1.5;
  Identification alone_plain(block(kLaw), plain.measurements, ellipse_options(true));
  Identification alone_turned(written, turned.measurements, ellipse_options(true));

  Eigen::VectorXd at(3);
  at << 0.3, 0.35, 8e10;  // not the case's values: the parameters reach the turned law
  const Identification::Prediction a = joint.predict(at, true);
  const Identification::Prediction b = alone_plain.predict(at, true);
  const Identification::Prediction c = alone_turned.predict(at, true);
  ASSERT_TRUE(a.ok && b.ok && c.ok) << a.message << b.message << c.message;
  const Eigen::Index n = b.values.size();
  std::printf("plain: %s\nturned: %s\n", b.index_sets.c_str(), c.index_sets.c_str());
  EXPECT_GT(c.num_slipping_nodes, 0);
  const double scale = std::max(b.values.cwiseAbs().maxCoeff(), c.values.cwiseAbs().maxCoeff());
  EXPECT_LE((a.values.head(n) - b.values).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LE((a.values.tail(n) - c.values).cwiseAbs().maxCoeff(), 1e-9 * scale);
  // The turned experiment differs from the plain one (else this test could not fail).
  EXPECT_GT((b.values - c.values).cwiseAbs().maxCoeff(), 1e-3 * scale);
  for (Eigen::Index k = 0; k < 3; ++k) {
    const double js = std::max(b.jacobian.col(k).cwiseAbs().maxCoeff(), c.jacobian.col(k).cwiseAbs().maxCoeff());
    EXPECT_LE((a.jacobian.col(k).head(n) - b.jacobian.col(k)).cwiseAbs().maxCoeff(), 1e-7 * js) << k;
    EXPECT_LE((a.jacobian.col(k).tail(n) - c.jacobian.col(k)).cwiseAbs().maxCoeff(), 1e-7 * js) << k;
  }
  // The turned experiment's Jacobian against central differences of the joint model (the law's
  // parameters enter through the turned vertices: w_j = μ_j R(φ) v_j).
  const Eigen::MatrixXd jacobian = a.jacobian;
  for (Eigen::Index k = 0; k < 3; ++k) {
    const double h = 1e-7 * at(k);
    Eigen::VectorXd plus = at, minus = at;
    plus(k) += h;
    minus(k) -= h;
    const Eigen::VectorXd up = joint.predict(plus).values, down = joint.predict(minus).values;
    const Eigen::VectorXd difference = (up - down) / (2 * h);
    const double js = jacobian.col(k).tail(n).cwiseAbs().maxCoeff();
    std::printf("column %d: |J| %.3e, |J - central difference| %.3e (turned), %.3e (plain)\n", static_cast<int>(k), js,
                (jacobian.col(k).tail(n) - difference.tail(n)).cwiseAbs().maxCoeff(),
                (jacobian.col(k).head(n) - difference.head(n)).cwiseAbs().maxCoeff());
    // Central differences of the 1e-13-accurate states agree to ~1e-5 relative for the plain
    // experiment too (measured: 7e-6 and 1.1e-5 of |J| for μ_x, μ_y); the rows of a wrongly
    // turned law would differ by O(1).
    EXPECT_LE((jacobian.col(k).tail(n) - difference.tail(n)).cwiseAbs().maxCoeff(), 1e-4 * js) << k;
  }
  EXPECT_EQ(a.num_slipping_nodes, b.num_slipping_nodes + c.num_slipping_nodes);
  EXPECT_NE(a.index_sets.find("plain: "), std::string::npos) << a.index_sets;
  EXPECT_NE(a.index_sets.find("; turned: "), std::string::npos) << a.index_sets;
}

TEST(IdentificationExperiments, RefusesBadExperimentsNamingThem) {
  IdentificationExperiment x;
  x.name = "a";
  Measurement total;
  total.quantity = MeasuredQuantity::kTotalNormalForce;
  x.measurements = {total};
  const auto error = [&](std::vector<IdentificationExperiment> list) {
    return error_of([&] { Identification id(block(kLaw), list, ellipse_options()); });
  };
  EXPECT_NE(error({}).find("no experiment"), std::string::npos);
  EXPECT_NE(error({x, x}).find("experiment[1].name = \"a\" is the name of experiment[0]"), std::string::npos) << error({x, x});
  IdentificationExperiment y = x;
  y.name = "b";
  y.measurements.clear();
  EXPECT_NE(error({x, y}).find("experiment[1] (\"b\"): no measurements"), std::string::npos) << error({x, y});
  y = x;
  y.name = "b";
  y.dirichlet_scale = {1.0, 2.0};
  EXPECT_NE(error({x, y}).find("experiment[1] (\"b\").dirichlet_scale: 2 scale(s); expected one for every [[dirichlet]] "
                               "table or one per table (the case has 1)"),
            std::string::npos)
      << error({x, y});
  y.dirichlet_scale = {};
  y.force_scale = {2.0};  // the block has no [[force]]
  EXPECT_NE(error({x, y}).find("force_scale: 1 scale(s)"), std::string::npos) << error({x, y});
  y.force_scale = {};
  y.load_scale = {kNaN};
  EXPECT_NE(error({x, y}).find("load_scale[0] = nan; expected a finite number"), std::string::npos) << error({x, y});
}

// cases3d/identify-lay: a tribometer that slides the specimen along x1 reads only the friction
// coefficient in that direction. Sliding along the lay ("along", 0°) gives μ_x and leaves μ_y not
// determined; turned by 90° ("across") the reverse; jointly both are recovered from the noise-free
// inline data.
TEST(IdentifyLayCase, EachExperimentAloneLeavesOneCoefficientUndeterminedJointlyBothAreRecovered) {
  const io::CaseDescription c = io::load_case("cases3d/identify-lay/case.toml");
  const io::IdentificationSetup& setup = c.required_identification();
  ASSERT_TRUE(setup.explicit_experiments);
  const std::vector<IdentificationExperiment> experiments = io::identification_experiments(setup, c.origin);
  ASSERT_EQ(experiments.size(), 2u);
  const Eigen::Vector2d truth(0.25, 0.4);

  Identification joint(c.body, experiments, setup.options);
  EXPECT_EQ(joint.case_parameters(), truth);
  const Identification::Summary s = joint.run();
  std::printf("joint: %s\n", s.brief_report().c_str());
  ASSERT_EQ(s.status, Status::kConverged) << s.message;
  ASSERT_EQ(s.estimates.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(s.estimates[static_cast<std::size_t>(k)].identifiability, Identifiability::kDetermined)
        << s.estimates[static_cast<std::size_t>(k)].note;
    EXPECT_NEAR(s.estimates[static_cast<std::size_t>(k)].value, truth(k), 1e-10) << s.estimates[static_cast<std::size_t>(k)].name;
    std::printf("  %s = %.15g (error %.2e)\n", s.estimates[static_cast<std::size_t>(k)].name.c_str(),
                s.estimates[static_cast<std::size_t>(k)].value, s.estimates[static_cast<std::size_t>(k)].value - truth(k));
  }
  ASSERT_EQ(s.experiments.size(), 2u);
  EXPECT_EQ(s.experiments[0].name, "along");
  EXPECT_EQ(s.experiments[1].name, "across");
  EXPECT_EQ(s.experiments[1].first_measurement, s.experiments[0].num_measurements);
  for (const auto& x : s.experiments) {
    EXPECT_GT(x.num_slipping_nodes, 0) << x.name;
    EXPECT_LE(x.rms_residual, 1e-8) << x.name;
  }

  // Each alone: its own coefficient to the same accuracy, the other not determined.
  for (std::size_t e = 0; e < 2; ++e) {
    Identification alone(c.body, std::vector<IdentificationExperiment>{experiments[e]}, setup.options);
    const Identification::Summary a = alone.run();
    std::printf("%s alone: %s\n", experiments[e].name.c_str(), a.brief_report().c_str());
    const std::size_t own = e, other = 1 - e;
    EXPECT_EQ(a.estimates[own].identifiability, Identifiability::kDetermined) << a.estimates[own].note;
    EXPECT_NEAR(a.estimates[own].value, truth(static_cast<Eigen::Index>(own)), 1e-10);
    EXPECT_EQ(a.estimates[other].identifiability, Identifiability::kNotDetermined) << a.estimates[other].note;
    EXPECT_TRUE(std::isnan(a.estimates[other].standard_deviation));
    EXPECT_NE(a.estimates[other].note.find("no measured quantity depends on it"), std::string::npos)
        << a.estimates[other].note;
  }
}

// ------------------------------------------------------------------------------------------
// The case-file tables.

const std::string kCase3d = frictopt::testing::block_header_3d("1.0", "0.5") +
                            frictopt::testing::top_dirichlet("[1.0e-5, 0.0, -1.0e-3]") +
                            frictopt::testing::design_table("[2, 2]", "0.0", "1.0e-3") + R"([contact.friction]
kind = "ellipse"
mu_x = 0.25
mu_y = 0.4
)";
const std::string kParameters = "[identification.parameters.mu_x]\nlower = 0.02\nupper = 1.5\n";

// The 1-based line of the `occurrence`-th (0-based) `needle` in `text`, as a case file's messages name it.
int line_of(const std::string& text, const std::string& needle, int occurrence = 0) {
  std::size_t at = text.find(needle);
  for (int k = 0; k < occurrence; ++k) at = text.find(needle, at + 1);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

std::string parse_error(const std::string& text) {
  return error_of([&] { (void)io::parse_case(text, "case.toml"); });
}

TEST(IdentificationTable, ReadsInlineMeasurementsInEveryLocationForm) {
  const std::string text = kCase3d + "[identification]\n" + kParameters + R"(
[[identification.measurement]]
quantity = "pressure"
location = "x=0.5;0.25"
value = 1.5e6
sigma = 1e4

[[identification.measurement]]
quantity = "tangential_force_x2"
location = 7
value = -2.0
sigma = 0.5

[[identification.measurement]]
quantity = "slip_x1"
location = [0.25, 0.75]
value = 1e-6
sigma = 1e-8

[[identification.measurement]]
quantity = "total_normal_force"
value = 3e5
sigma = 3e3

[[identification.measurement]]
quantity = "total_tangential_force_x1"
location = "all"
value = -1e4
sigma = 1e2
)";
  const io::CaseDescription c = io::parse_case(text, "cases/x/case.toml");
  const io::IdentificationSetup& setup = c.required_identification();
  ASSERT_EQ(setup.experiments.size(), 1u);
  EXPECT_FALSE(setup.experiments[0].measurements.has_value());  // no CSV file is needed
  const std::vector<Measurement>& rows = setup.experiments[0].inline_measurements;
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].quantity, MeasuredQuantity::kPressure);
  ASSERT_TRUE(rows[0].point.has_value());
  EXPECT_EQ(*rows[0].point, Eigen::Vector2d(0.5, 0.25));
  EXPECT_EQ(rows[0].value, 1.5e6);
  EXPECT_EQ(rows[0].sigma, 1e4);
  EXPECT_EQ(rows[1].node, 7);
  EXPECT_EQ(*rows[2].point, Eigen::Vector2d(0.25, 0.75));
  EXPECT_EQ(rows[3].quantity, MeasuredQuantity::kTotalNormalForce);
  EXPECT_EQ(rows[4].node, -1);
  EXPECT_EQ(rows[0].label, "cases/x/case.toml:" + std::to_string(line_of(text, "[[identification.measurement]]")) +
                               ": identification.measurement[0]");
  // They are the case's measurements, and they resolve on the body.
  const std::vector<IdentificationExperiment> x = io::identification_experiments(setup, c.origin);
  ASSERT_EQ(x.size(), 1u);
  EXPECT_EQ(x[0].measurements.size(), 5u);
  Identification id(c.body, x, setup.options);
  EXPECT_GE(id.measurements()[0].node, 0);
}

TEST(IdentificationTable, RefusesBadInlineMeasurementsAndMissingOnesNamingThem) {
  const std::string head = kCase3d + "[identification]\n" + kParameters;
  const auto row = [](const std::string& body) { return "[[identification.measurement]]\n" + body; };
  const std::string bad_quantity = head + row("quantity = \"normal_forse\"\nlocation = 1\nvalue = 1\nsigma = 1\n");
  EXPECT_NE(parse_error(bad_quantity)
                .find("case.toml:" + std::to_string(line_of(bad_quantity, "quantity = \"normal_forse")) +
                      ": identification.measurement[0]: quantity = \"normal_forse\"; expected one of"),
            std::string::npos)
      << parse_error(bad_quantity);
  const std::string bad_sigma = head + row("quantity = \"normal_force\"\nlocation = 1\nvalue = 1\nsigma = 0\n");
  EXPECT_NE(parse_error(bad_sigma)
                .find("case.toml:" + std::to_string(line_of(bad_sigma, "sigma = 0")) +
                      ": identification.measurement[0].sigma = 0; expected a standard deviation > 0"),
            std::string::npos)
      << parse_error(bad_sigma);
  EXPECT_NE(parse_error(head + row("quantity = \"normal_force\"\nvalue = 1\nsigma = 1\n"))
                .find("identification.measurement[0].location is missing"),
            std::string::npos);
  EXPECT_NE(parse_error(head + row("quantity = \"total_normal_force\"\nlocation = \"x=0.5;0.5\"\nvalue = 1\nsigma = 1\n"))
                .find("expected \"all\" or empty for the sum total_normal_force"),
            std::string::npos);
  EXPECT_NE(parse_error(head + row("quantity = \"pressure\"\nlocation = [0.5, 0.5, 0.5]\nvalue = 1\nsigma = 1\n"))
                .find("identification.measurement[0].location = [0.5, 0.5, 0.5]; expected a point [x1, x2]"),
            std::string::npos);
  EXPECT_NE(parse_error(head + row("quantity = \"pressure\"\nlocation = \"x=0.5;0.5\"\nvalue = 1\nsigma = 1\nnode = 3\n"))
                .find("node"),
            std::string::npos);
  // No measurement anywhere: the case parses (Python may pass a list), identify refuses it.
  const io::CaseDescription c = io::parse_case(head, "case.toml");
  EXPECT_NE(error_of([&] { (void)io::identification_experiments(c.required_identification(), c.origin); })
                .find("case.toml: [identification] gives no measurements; expected measurements = \"file.csv\""),
            std::string::npos);
}

TEST(IdentificationTable, ReadsExperimentsAndRefusesBadOnesNamingThem) {
  const std::string head = kCase3d + "[identification]\n" + kParameters;
  const std::string along = R"(
[[identification.experiment]]
name = "along"
measurements = "along.csv"
)";
  const std::string across = R"(
[[identification.experiment]]
name = "across"
orientation_deg = 90
dirichlet_scale = 0.8
[[identification.experiment.measurement]]
quantity = "total_tangential_force_x1"
value = -3.0
sigma = 0.1
)";
  const io::CaseDescription c = io::parse_case(head + along + across, "cases/x/case.toml");
  const io::IdentificationSetup& setup = c.required_identification();
  ASSERT_TRUE(setup.explicit_experiments);
  ASSERT_EQ(setup.experiments.size(), 2u);
  EXPECT_EQ(setup.experiments[0].name, "along");
  EXPECT_EQ(setup.experiments[0].measurements, std::filesystem::path("cases/x/along.csv"));
  EXPECT_EQ(setup.experiments[0].orientation, 0.0);
  EXPECT_EQ(setup.experiments[1].name, "across");
  EXPECT_DOUBLE_EQ(setup.experiments[1].orientation, std::numbers::pi / 2);
  EXPECT_EQ(setup.experiments[1].dirichlet_scale, std::vector<double>{0.8});
  ASSERT_EQ(setup.experiments[1].inline_measurements.size(), 1u);
  EXPECT_EQ(setup.experiments[1].inline_measurements[0].label,
            "cases/x/case.toml:" +
                std::to_string(line_of(head + along + across, "[[identification.experiment.measurement]]")) +
                ": identification.experiment[1].measurement[0]");

  const auto expect = [&](const std::string& text, const std::string& message) {
    const std::string e = parse_error(text);
    EXPECT_NE(e.find(message), std::string::npos) << e;
  };
  expect(kCase3d + "[identification]\nmeasurements = \"m.csv\"\n" + kParameters + along,
         "identification.measurements with [[identification.experiment]] tables; expected the measurements inside each "
         "experiment");
  expect(head + along + along, "identification.experiment[1].name = \"along\" is the name of identification.experiment[0]");
  expect(head + "[[identification.experiment]]\nname = \"empty\"\n",
         "identification.experiment[0].measurements is missing; expected the measurements of experiment \"empty\"");
  expect(head + "[[identification.experiment]]\nname = \"a/b\"\nmeasurements = \"x.csv\"\n",
         "identification.experiment[0].name = \"a/b\"; expected a name of 1 to 64 letters");
  expect(head + "[[identification.experiment]]\ndirichlet_scale = [0.8, 1.0]\nmeasurements = \"x.csv\"\n",
         "identification.experiment[0].dirichlet_scale = [0.8, 1]; expected a number (every [[dirichlet]] table) or a "
         "list of 1 numbers (one per table)");
  expect(head + "[[identification.experiment]]\nforce_scale = 2\nmeasurements = \"x.csv\"\n",
         "identification.experiment[0].force_scale = 2: the case has no [[force]] table to scale");
  expect(head + "[[identification.experiment]]\norientation_deg = 400\nmeasurements = \"x.csv\"\n",
         "identification.experiment[0].orientation_deg = 400; expected an angle in [-360, 360] degrees");
  expect(head + "[[identification.experiment]]\nturn = 1\nmeasurements = \"x.csv\"\n", "turn");
  // Unnamed experiments get distinct default names.
  const io::CaseDescription d =
      io::parse_case(head + "[[identification.experiment]]\nmeasurements = \"a.csv\"\n[[identification.experiment]]\n"
                            "measurements = \"b.csv\"\n",
                     "case.toml");
  EXPECT_EQ(d.required_identification().experiments[1].name, "experiment_1");
}

TEST(IdentificationTable, RefusesATurnedExperimentIn2D) {
  const std::string text = R"(
[geometry]
dim = 2
a = 1.0
height = 0.5
[mesh]
cells = [8, 4]
[material]
young = 7e10
poisson = 0.3
[[dirichlet]]
face = "top"
displacement = [1e-5, -1e-3]
[design]
control_points = [3]
initial = 0.0
upper_bound = 1e-3
[contact.friction]
kind = "isotropic"
mu = 0.3
[identification]
[identification.parameters.mu_plus]
lower = 0.02
upper = 1.5
[[identification.experiment]]
orientation_deg = 90
measurements = "x.csv"
)";
  const std::string e = parse_error(text);
  EXPECT_NE(e.find("identification.experiment[0].orientation_deg = 90; expected 0 in 2D"), std::string::npos) << e;
}

}  // namespace
}  // namespace frictopt::study
