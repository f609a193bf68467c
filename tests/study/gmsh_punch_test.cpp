// SPDX-License-Identifier: MIT
// cases3d/gmsh-punch imports the demo's body from Gmsh (punch.geo extrudes the structured grid's
// nodes; the "sweep" extension is the grid's vertical morph): it must reproduce the demo
// cases3d/punch-anisotropic — Θ, the contact forces λ and the subgradient ξ at α⁰.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>

#include "frictopt/io/case_file.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {
namespace {

namespace fs = std::filesystem;

TEST(GmshPunch, ReproducesTheStructuredDemoNodeForNode) {
  const fs::path root(FRICTOPT_SOURCE_DIR);
  const io::CaseDescription structured = io::load_case(root / "cases3d/punch-anisotropic/case.toml");
  const io::CaseDescription imported = io::load_case(root / "cases3d/gmsh-punch/case.toml");
  ASSERT_TRUE(imported.body.imported_mesh.has_value());
  ElasticBody structured_body(structured.body), imported_body(imported.body);
  ASSERT_EQ(imported_body.mesh().num_nodes(), structured_body.mesh().num_nodes());
  ShapeOracle structured_oracle(structured_body, structured.required_cost());
  ShapeOracle imported_oracle(imported_body, imported.required_cost());
  const Eigen::VectorXd alpha = structured.body.initial_design;
  ASSERT_EQ(imported.body.initial_design, alpha);
  const Evaluation& s = structured_oracle.evaluate_design(alpha);
  const Evaluation& i = imported_oracle.evaluate_design(alpha);
  ASSERT_TRUE(s.ok) << s.message;
  ASSERT_TRUE(i.ok) << i.message;
  const double theta_error = std::abs(i.value - s.value) / std::abs(s.value);
  const double xi_error = (i.subgradient - s.subgradient).norm() / s.subgradient.norm();
  // λ per contact node, matched by the nodes' coordinates.
  const auto lambdas = [](ShapeOracle& oracle, const ElasticBody& body, const Eigen::VectorXd& a) {
    std::map<std::tuple<double, double, double>, double> by_position;
    const contact::ContactState& cs = oracle.state(a).contact->state;
    const Eigen::MatrixXd& X = body.mesh().reference_positions();
    const std::vector<int>& nodes = body.contact_boundary()->nodes();
    for (std::size_t k = 0; k < nodes.size(); ++k)
      by_position[{X(nodes[k], 0), X(nodes[k], 1), X(nodes[k], 2)}] = cs.lambda(static_cast<Eigen::Index>(k));
    return by_position;
  };
  const auto ls = lambdas(structured_oracle, structured_body, alpha);
  const auto li = lambdas(imported_oracle, imported_body, alpha);
  ASSERT_EQ(ls.size(), li.size());
  double lambda_scale = 0.0, lambda_error = 0.0;
  for (const auto& [x, lambda] : ls) {
    ASSERT_TRUE(li.count(x)) << "a contact node of the grid is missing in the imported mesh";
    lambda_scale = std::max(lambda_scale, std::abs(lambda));
    lambda_error = std::max(lambda_error, std::abs(li.at(x) - lambda));
  }
  RecordProperty("theta_relative_error", std::to_string(theta_error));
  RecordProperty("xi_relative_error", std::to_string(xi_error));
  RecordProperty("lambda_relative_error", std::to_string(lambda_error / lambda_scale));
  std::printf("Θ %.17g vs %.17g: rel %.3e; ξ rel %.3e; λ max rel %.3e\n", i.value, s.value, theta_error, xi_error,
              lambda_error / lambda_scale);
  EXPECT_LE(theta_error, 1e-10);
  EXPECT_LE(xi_error, 1e-10);
  EXPECT_LE(lambda_error, 1e-10 * lambda_scale);
}

}  // namespace
}  // namespace frictopt::study
