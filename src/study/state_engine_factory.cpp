// SPDX-License-Identifier: MIT
// The one place that knows every engine: a new engine is one class and one case below.
#include "frictopt/study/state_engine_factory.hpp"

#include "direct_engine.hpp"
#include "frictopt/core/error.hpp"
#ifdef FRICTOPT_HAVE_PETSC
#include "petsc_engine.hpp"
#endif

namespace frictopt::study {

std::unique_ptr<StateEngine> make_state_engine(const BodyDefinition& definition, const EngineSetup& setup) {
  switch (definition.engine.kind) {
    case StateEngine::kDirect:
      return std::make_unique<DirectEngine>(definition, setup);
    case StateEngine::kPetsc:
#ifdef FRICTOPT_HAVE_PETSC
      return std::make_unique<PetscEngine>(definition, setup);
#else
      throw InvalidInput(
          "solver.engine = \"petsc\": this frictopt was built without PETSc; expected engine = \"direct\", or a "
          "build with petsc-dev installed (FRICTOPT_WITH_PETSC, docs/petsc-engine.md)");
#endif
  }
  throw InvalidInput("solver.engine: an engine this build does not know; expected \"direct\" or \"petsc\"");
}

}  // namespace frictopt::study
