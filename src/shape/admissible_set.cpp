// SPDX-License-Identifier: MIT
#include "frictopt/shape/admissible_set.hpp"

#include <fmt/format.h>

#include <vector>

#include "frictopt/core/error.hpp"

namespace frictopt::shape {

LinearConstraints make_admissible_set(const BezierShape& shape, const AdmissibleSetParameters& p) {
  if (!(p.upper_bound > 0))
    throw InvalidInput(fmt::format("design.upper_bound = {}; expected > 0", p.upper_bound));
  if (!(p.height > p.upper_bound))
    throw InvalidInput(fmt::format(
        "design.upper_bound = {}; expected < geometry.height = {} (a control point above the "
        "top would invert elements)",
        p.upper_bound, p.height));
  if (p.slope_bound && !(*p.slope_bound > 0))
    throw InvalidInput(fmt::format("design.slope_bound = {}; expected > 0", *p.slope_bound));

  const int d = shape.num_controls();
  const auto m = shape.control_net();
  const auto extent = shape.extents();
  LinearConstraints c;
  c.variable_name = "alpha";
  c.lower = Eigen::VectorXd::Zero(d);
  c.upper = Eigen::VectorXd::Constant(d, p.upper_bound);

  std::vector<Eigen::VectorXd> rows;
  std::vector<double> rhs;
  if (p.slope_bound) {
    const int directions = shape.dim() - 1;
    for (int dir = 0; dir < directions; ++dir) {
      const double scale = p.slope_scaling == SlopeScaling::kExact ? extent[dir] : 1.0;
      const double delta = scale * *p.slope_bound / (m[dir] - 1);
      for (int j = 0; j < m[1]; ++j)
        for (int i = 0; i < m[0]; ++i) {
          const int i2 = dir == 0 ? i + 1 : i, j2 = dir == 1 ? j + 1 : j;
          if (i2 >= m[0] || j2 >= m[1]) continue;
          const int k = i + m[0] * j, k2 = i2 + m[0] * j2;
          for (int sign : {+1, -1}) {
            Eigen::VectorXd row = Eigen::VectorXd::Zero(d);
            row(k2) = sign;
            row(k) = -sign;
            rows.push_back(row);
            rhs.push_back(delta);
            // Name the row as the difference it bounds: "alpha[6] - alpha[5] <= δ" (sign +)
            // or "alpha[5] - alpha[6] <= δ" (sign −).
            const int hi = sign > 0 ? k2 : k, lo = sign > 0 ? k : k2;
            c.inequality_names.push_back(
                shape.dim() == 2 ? fmt::format("slope alpha[{}] - alpha[{}]", hi, lo)
                                 : fmt::format("slope x{} alpha({},{}) - alpha({},{})", dir + 1,
                                               hi % m[0], hi / m[0], lo % m[0], lo / m[0]));
          }
        }
    }
  }
  c.A_in.resize(static_cast<Eigen::Index>(rows.size()), d);
  c.b_in.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    c.A_in.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
    c.b_in(static_cast<Eigen::Index>(r)) = rhs[r];
  }

  if (p.volume) {
    const double base = shape.base_measure();
    const double sum = d * (base * p.height - *p.volume) / base;
    const double mean_height = sum / d;
    if (mean_height < 0 || mean_height > p.upper_bound)
      throw InvalidInput(fmt::format(
          "design.volume = {}; the volume asks for a mean bottom height {:.6g}, expected within "
          "[0, upper_bound = {}] (the admissible set would be empty)",
          *p.volume, mean_height, p.upper_bound));
    c.A_eq = Eigen::MatrixXd::Ones(1, d);
    c.b_eq = Eigen::VectorXd::Constant(1, sum);
    c.equality_names = {"volume: sum of alpha"};
  } else {
    c.A_eq.resize(0, d);
    c.b_eq.resize(0);
  }
  return c;
}

}  // namespace frictopt::shape
