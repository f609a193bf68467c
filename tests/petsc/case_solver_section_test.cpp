// SPDX-License-Identifier: MIT
// The engine keys of [solver] (src/io/case_solver_section.cpp) through the case parser, and the
// engine selected by a case running end to end.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {
namespace {

// The shipped punch case at a coarse resolution with `solver` appended.
std::string punch_with(const std::string& solver) {
  std::ifstream in("cases3d/punch/case.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string toml = text.str();
  const std::string cells = "cells = [24, 24, 12]";
  toml.replace(toml.find(cells), cells.size(), "cells = [8, 8, 4]");
  return toml + "\n" + solver + "\n";
}

std::string error_of(const std::string& solver) {
  try {
    (void)parse_case(punch_with(solver), "case.toml");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(CaseSolverSection, DefaultsToTheDirectEngine) {
  const CaseDescription c = parse_case(punch_with(""), "case.toml");
  EXPECT_EQ(c.body.engine.kind, study::StateEngine::kDirect);
}

TEST(CaseSolverSection, ReadsThePetscEngineAndItsOptions) {
  const CaseDescription c = parse_case(
      punch_with("[solver]\nengine = \"petsc\"\npetsc_options = \"-ksp_type bcgs\"\n[solver.newton]\nmax_iterations = 30\n"
                 "relative_tolerance = 1e-9"),
      "case.toml");
  EXPECT_EQ(c.body.engine.kind, study::StateEngine::kPetsc);
  EXPECT_EQ(c.body.engine.petsc_options, "-ksp_type bcgs");
  EXPECT_EQ(c.body.engine.max_iterations, 30);
  EXPECT_EQ(c.body.engine.relative_tolerance, 1e-9);
}

TEST(CaseSolverSection, RejectsBadEngineSettingsNamingTheField) {
  EXPECT_NE(error_of("[solver]\nengine = \"cuda\"").find("solver.engine"), std::string::npos);
  EXPECT_NE(error_of("[solver]\nengine = \"cuda\"").find("one of direct, petsc"), std::string::npos);
  EXPECT_NE(error_of("[solver]\npetsc_options = \"-ksp_type cg\"").find("needs engine = \"petsc\""), std::string::npos);
  EXPECT_NE(error_of("[solver]\nengine = \"petsc\"\n[solver.newton]\nmax_iterations = 0").find("solver.newton.max_iterations"),
            std::string::npos);
  EXPECT_NE(error_of("[solver]\nengine = \"petsc\"\n[solver.newton]\nsteps = 3").find("steps"), std::string::npos);
}

TEST(CaseSolverSection, AnUnknownPetscOptionIsInvalidInputAtTheFirstSolve) {
  const CaseDescription c = parse_case(punch_with("[solver]\nengine = \"petsc\"\npetsc_options = \"-pc_type gamg -pc_gamg_thresh 0.01\""), "case.toml");
  study::ElasticBody body(c.body);
  try {
    (void)body.solve(c.body.initial_design);
    FAIL() << "the misspelled option was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("-pc_gamg_thresh"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace frictopt::io
