// SPDX-License-Identifier: MIT
#include "case_material_section.hpp"

#include <fmt/format.h>

#include "case_table_common.hpp"
#include "text_input.hpp"

namespace frictopt::io::detail {
namespace {

// Physical bounds (docs/case-format.md, "Physical bounds"): beyond them the numbers are
// outside linear elasticity or outside double precision, and the solvers would fail with
// messages that do not name the field.
constexpr double kMinYoung = 1.0;        // Pa: softer than any solid (gels are ~1e2 Pa)
constexpr double kMaxYoung = 1e13;       // Pa: stiffer than diamond (1.2e12 Pa)
constexpr double kMaxPoisson = 0.49;     // Q1 elements lock beyond; λ/μ = 49 here

fem::IsotropicMaterial read_material(const TableReader& r, int dim) {
  fem::IsotropicMaterial m;
  m.young = r.required_number("young", "a number > 0 (Young's modulus, Pa)");
  if (!(m.young > 0)) r.fail_value("young", "young > 0");
  if (!(m.young >= kMinYoung && m.young <= kMaxYoung))
    r.fail_value("young", fmt::format("{:g} Pa <= young <= {:g} Pa (Young's modulus in Pa; docs/case-format.md, "
                                      "\"Physical bounds\")",
                                      kMinYoung, kMaxYoung));
  m.poisson = r.required_number("poisson", "a number in [0, 0.5) (Poisson's ratio)");
  if (!(m.poisson >= 0 && m.poisson < 0.5)) r.fail_value("poisson", "0 <= poisson < 0.5");
  if (!(m.poisson <= kMaxPoisson))
    r.fail_value("poisson", fmt::format("0 <= poisson <= {} (Q1 elements lock for a nearly incompressible "
                                        "material and the solvers lose their accuracy; docs/case-format.md)",
                                        kMaxPoisson));
  if (dim == 3 && r.has("model"))
    r.fail("model", fmt::format("{} = {} is only allowed in 2D, but geometry.dim = 3",
                                r.field("model"), describe(*r.node("model"))));
  if (auto model = read_enum(r, "model", fem::kPlaneModelNames)) m.plane_model = *model;
  return m;
}

}  // namespace

fem::IsotropicMaterial read_material_section(const TableReader& top, std::string_view origin, int dim) {
  return read_material(required_table(top, "material", origin, {"young", "poisson", "model"}), dim);
}

}  // namespace frictopt::io::detail
