// SPDX-License-Identifier: MIT
// [solver.coulomb] method in a case file (docs/case-format.md, "[solver]"): the four spellings,
// the default "automatic", a wrong value and a fixed point asked of the PETSc engine refused
// naming the field, its value and the expectation.
#include <gtest/gtest.h>

#include <string>

#include "common/case_text.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"

namespace frictopt::contact {
namespace {

std::string case_text(const std::string& solver) {
  return frictopt::testing::block_header_3d("1.0", "0.5") + frictopt::testing::top_dirichlet("[0.0, 0.0, -1e-4]") +
         frictopt::testing::design_table("[2, 2]", "[0.0, 0.0, 0.0, 0.0]", "1e-3") +
         "[contact.friction]\nkind = \"disc_exact\"\nmu = 0.3\n" + solver;
}

CoulombMethod method_of(const std::string& solver) {
  return io::parse_case(case_text(solver), "case.toml").body.contact->coulomb.method;
}

TEST(CoulombMethodCase, SpellingsAndDefault) {
  EXPECT_EQ(method_of(""), CoulombMethod::kAutomatic);
  EXPECT_EQ(method_of("[solver.coulomb]\nmax_iterations = 20\n"), CoulombMethod::kAutomatic);
  EXPECT_EQ(method_of("[solver.coulomb]\nmethod = \"fixed_point\"\n"), CoulombMethod::kFixedPoint);
  EXPECT_EQ(method_of("[solver.coulomb]\nmethod = \"split\"\n"), CoulombMethod::kSplit);
  EXPECT_EQ(method_of("[solver.coulomb]\nmethod = \"semismooth_newton\"\n"), CoulombMethod::kSemismoothNewton);
  EXPECT_EQ(method_of("[solver.coulomb]\nmethod = \"automatic\"\n"), CoulombMethod::kAutomatic);
}

TEST(CoulombMethodCase, WrongValuesAreRefusedNamingTheField) {
  try {
    (void)method_of("[solver.coulomb]\nmethod = \"newton\"\n");
    FAIL();
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("solver.coulomb.method"), std::string::npos) << m;
    EXPECT_NE(m.find("newton"), std::string::npos) << m;
    EXPECT_NE(m.find("one of automatic, fixed_point, split, semismooth_newton"), std::string::npos) << m;
  }
  try {
    (void)method_of("[solver]\nengine = \"petsc\"\n[solver.coulomb]\nmethod = \"fixed_point\"\n");
    FAIL();
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    // A build without PETSc may refuse the engine first; either way the message names [solver].
    EXPECT_NE(m.find("solver."), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace frictopt::contact
