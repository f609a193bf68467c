// SPDX-License-Identifier: MIT
// TOML blocks that many tests' case texts share (docs/case-format.md). Values are passed as the
// literal TOML text, not as numbers, so a test's case reads exactly as the file it stands for
// (and replacements on the text, as in invalid_case.hpp's `replaced`, still find their lines).
#pragma once

#include <string>
#include <string_view>

namespace frictopt::testing {

/// [geometry], [mesh] and [material] of a 3D block `side` × `side` × `height` on a `cells` grid,
/// aluminium (E = 70 GPa, ν = 0.33). Starts with a newline, as the tests' raw strings do.
inline std::string block_header_3d(std::string_view side, std::string_view height,
                                   std::string_view cells = "[4, 4, 2]") {
  std::string t = "\n[geometry]\ndim = 3\n";
  t.append("a = ").append(side).append("\nb = ").append(side).append("\nheight = ").append(height);
  t.append("\n[mesh]\ncells = ").append(cells);
  t.append("\n[material]\nyoung = 7.0e10\npoisson = 0.33\n");
  return t;
}

/// One [[dirichlet]] table on the top face (the rigid plate): `displacement`, restricted to
/// `components` when given.
inline std::string top_dirichlet(std::string_view displacement, std::string_view components = "") {
  std::string t = "[[dirichlet]]\nface = \"top\"\n";
  if (!components.empty()) t.append("components = ").append(components).append("\n");
  t.append("displacement = ").append(displacement).append("\n");
  return t;
}

/// The [design] table's Bézier net, initial heights and bound C0; further [design] keys may follow.
inline std::string design_table(std::string_view control_points, std::string_view initial,
                                std::string_view upper_bound) {
  std::string t = "[design]\ncontrol_points = ";
  t.append(control_points).append("\ninitial = ").append(initial).append("\nupper_bound = ").append(upper_bound);
  t.append("\n");
  return t;
}

/// The CLI tests' small flat block (0.1 × 0.1 × 0.05 on 4 × 4 × 2 cells, 2 × 2 net at zero,
/// C0 = 1e-3, exact Coulomb disc μ = 0.3) pressed down by 1e-6 (table 1: component z) and dragged
/// by 2e-7 along x (table 2: components x, y) by its top; programs scale the two tables.
inline std::string pressed_dragged_block_3d() {
  return block_header_3d("0.1", "0.05") + top_dirichlet("[0.0, 0.0, -1.0e-6]", "[2]") +
         top_dirichlet("[2.0e-7, 0.0, 0.0]", "[0, 1]") + design_table("[2, 2]", "[0.0, 0.0, 0.0, 0.0]", "1.0e-3") +
         "[contact.friction]\nkind = \"disc_exact\"\nmu = 0.3\n";
}

/// The 1 m block pushed by a traction on its left face and pressed by its top plate (one [[load]],
/// one [[dirichlet]]), flat bottom (2 × 2 controls), isotropic μ = 0.3: the parser tests of
/// loading programs and load cases append their tables.
inline std::string pushed_block_3d() {
  return block_header_3d("1.0", "0.5") + R"([[load]]
face = "left"
traction = [1.0e5, 0.0, 0.0]
)" + top_dirichlet("[0.0, 0.0, -1.0e-4]") +
         design_table("[2, 2]", "[0.0, 0.0, 0.0, 0.0]", "1.0e-3") + R"([contact.friction]
kind = "isotropic"
mu = 0.3
)";
}

}  // namespace frictopt::testing
