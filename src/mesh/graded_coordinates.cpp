// SPDX-License-Identifier: MIT
#include "frictopt/mesh/graded_coordinates.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "frictopt/core/error.hpp"

namespace frictopt::mesh {

std::vector<double> uniform_coordinates(double length, int cells) {
  std::vector<double> x(static_cast<std::size_t>(cells) + 1);
  for (int i = 0; i <= cells; ++i) x[static_cast<std::size_t>(i)] = length * i / cells;
  return x;
}

namespace {

// Length covered by k cells of sizes h·r, …, h·r^k.
double geometric_length(double h, double r, int k) {
  double sum = 0, term = h;
  for (int j = 0; j < k; ++j) sum += (term *= r);
  return sum;
}

// Fewest cells that fill a side of length `side` next to box cells of size h when they may
// grow by `growth` per cell; kInfeasible when even `cells` of them do not reach.
constexpr int kInfeasible = std::numeric_limits<int>::max();
int fewest_side_cells(double side, double h, double growth, int cells) {
  if (side <= 0) return 0;
  double sum = 0, term = h;
  for (int k = 1; k <= cells; ++k) {
    sum += (term *= growth);
    if (sum >= side) return k;
  }
  return kInfeasible;
}

// Most cells that fit on a side without being smaller than h (ratio r >= 1). The relative
// slack absorbs the rounding of side/h when the side is an exact multiple of h.
int most_side_cells(double side, double h) { return side <= 0 ? 0 : static_cast<int>(std::floor(side / h * (1 + 1e-12))); }

// The ratio r in [1, growth] with geometric_length(h, r, k) = side, by bisection: the length is
// increasing in r, and bisection to the last bit is cheap for the few hundred cells of a grid.
double side_ratio(double side, double h, int k, double growth) {
  double lo = 0.5, hi = growth;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (geometric_length(h, mid, k) < side ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The construction of graded_coordinates without its input checks: std::nullopt when `cells`
// cannot grade [0, length] toward [lo, hi] with ratios in [1, growth].
std::optional<std::vector<double>> graded_or_none(double length, int cells, double lo, double hi, double growth) {
  const double left = lo, right = length - hi, width = hi - lo;
  // The finest box cells first: m = cells, cells − 1, …; the first m whose sides can be filled
  // with ratios in [1, growth] by the cells that remain.
  for (int m = cells; m >= 1; --m) {
    const double h = width / m;
    const int rest = cells - m;
    const int min_left = fewest_side_cells(left, h, growth, rest), min_right = fewest_side_cells(right, h, growth, rest);
    if (min_left == kInfeasible || min_right == kInfeasible) continue;
    const int max_left = most_side_cells(left, h), max_right = most_side_cells(right, h);
    if (min_left > max_left || min_right > max_right) continue;  // a side shorter than its cells
    if (min_left + min_right > rest || max_left + max_right < rest) continue;
    // Distribute the remaining cells: each goes to the side whose cells are the largest on
    // average (the one that needs the steeper growth).
    int k_left = min_left, k_right = min_right;
    for (int extra = rest - min_left - min_right; extra > 0; --extra) {
      const bool can_left = k_left < max_left, can_right = k_right < max_right;
      const double mean_left = can_left ? left / (k_left + 1) : -1, mean_right = can_right ? right / (k_right + 1) : -1;
      (mean_left >= mean_right ? k_left : k_right) += 1;
    }
    std::vector<double> x(static_cast<std::size_t>(cells) + 1);
    const double r_left = k_left > 0 ? side_ratio(left, h, k_left, growth) : 1.0;
    const double r_right = k_right > 0 ? side_ratio(right, h, k_right, growth) : 1.0;
    // Left side, from the box edge outward; the outermost line is the side itself.
    double position = lo, size = h;
    for (int j = 1; j <= k_left; ++j) {
      size *= r_left;
      position -= size;
      x[static_cast<std::size_t>(k_left - j)] = j == k_left ? 0.0 : position;
    }
    for (int i = 0; i <= m; ++i) x[static_cast<std::size_t>(k_left + i)] = i == m ? hi : lo + width * i / m;
    position = hi;
    size = h;
    for (int j = 1; j <= k_right; ++j) {
      size *= r_right;
      position += size;
      x[static_cast<std::size_t>(k_left + m + j)] = j == k_right ? length : position;
    }
    return x;
  }
  return std::nullopt;
}

}  // namespace

std::vector<double> graded_coordinates(double length, int cells, double lo, double hi, double growth,
                                       const std::string& field) {
  if (!(growth > 1.0 && growth <= 2.0))
    throw InvalidInput(fmt::format("mesh.growth = {}; expected 1 < growth <= 2 for a graded grid", growth));
  if (!(lo >= 0 && hi <= length && lo < hi))
    throw InvalidInput(fmt::format("mesh.refine_box edges {} .. {} m along {}; expected 0 <= min < max <= {} m",
                                   lo, hi, field, length));
  if (auto x = graded_or_none(length, cells, lo, hi, growth)) return std::move(*x);
  throw InvalidInput(fmt::format(
      "{} = {} cells cannot grade [0, {}] m toward the refinement box [{}, {}] m with mesh.growth = {}; expected "
      "more cells, a larger growth, or box edges at a side or at least one refined cell away from it",
      field, cells, length, lo, hi, growth));
}

std::vector<double> contact_layer_coordinates(double height, int layers, double fine_depth, double growth) {
  if (!(growth > 1.0 && growth <= 2.0))
    throw InvalidInput(fmt::format("mesh.vertical_growth = {}; expected 1 < vertical_growth <= 2", growth));
  if (!(fine_depth > 0 && fine_depth < height))
    throw InvalidInput(fmt::format("mesh.fine_depth = {} m; expected 0 < fine_depth < geometry.height = {} m "
                                   "(the depth below the contact surface that keeps the thinnest layers)",
                                   fine_depth, height));
  // The fine zone [0, fine_depth] is a refinement interval at one end of [0, height]: the same
  // construction as the in-plane columns, with no cells on its lower side.
  if (auto z = graded_or_none(height, layers, 0.0, fine_depth, growth)) return std::move(*z);
  throw InvalidInput(fmt::format(
      "mesh.cells[vertical] = {} layers cannot keep equal layers down to mesh.fine_depth = {} m and grow by at most "
      "mesh.vertical_growth = {} up to geometry.height = {} m; expected more layers, a larger vertical_growth or a "
      "larger fine_depth",
      layers, fine_depth, growth, height));
}

}  // namespace frictopt::mesh
