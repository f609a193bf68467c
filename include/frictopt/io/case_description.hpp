// SPDX-License-Identifier: MIT
// A parsed case file: the numeric modules' own definitions, filled by the parser in one step
// (io/case_file.hpp; schema docs/case-format.md). There is no second, io-side copy of the
// body, cost or optimizer settings and no re-mapping step: what the parser validated is what
// the solvers get. Only the output settings are io's own.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/identification.hpp"
#include "frictopt/study/loading_program.hpp"
#include "frictopt/study/tribometer.hpp"

namespace frictopt::io {

/// [output].
struct OutputSpec {
  bool vtk = true;   ///< write .vtu (and a .pvd for series)
  int every = 1;     ///< write every n-th optimization iterate, >= 1
  std::string name;  ///< base name of output files; default the case file stem
};

/// [identification]: identify friction coefficients (and E) from measurements (docs/identification.md).
struct IdentificationSetup {
  /// The measurement CSV; a relative path is resolved against the case file's directory.
  std::filesystem::path measurements;
  /// The parameters (one entry per identified scalar: "mu_vertices[j]" per vertex), bounds,
  /// robust loss and iteration limit; the other options keep study's defaults.
  study::Identification::Options options;
};

/// A validated case. Every field satisfies the ranges documented in docs/case-format.md and
/// the dimension-dependent sizes match the body's dimension: consumers may trust it without
/// re-validating.
struct CaseDescription {
  std::string origin;  ///< where it came from (file path or origin name), for messages
  /// Shape, mesh resolution, material, Γ_u, Γ_p, Υ, α⁰ and the contact law with its solver
  /// options; body.name is output.name.
  study::BodyDefinition body;
  std::optional<study::CostDefinition> cost;  ///< [cost]; absent: only `solve` is possible
  /// The bundle trust options: study::default_study_options(body) with the case's
  /// [optimization] overrides.
  optim::BundleTrust::Options optimization;
  OutputSpec output;
  std::optional<IdentificationSetup> identification;  ///< [identification], absent: no `identify`
  /// [[program.step]]: a quasi-static loading program (`solve` runs it step by step).
  std::optional<study::LoadingProgramDefinition> program;
  /// [experiment]: the virtual tribometer (`frictopt experiment`).
  std::optional<study::TribometerDefinition> experiment;
  /// The problem the case defines, normalized: every key of the file except the run controls
  /// [optimization] and [output], as dotted key ("material.young", "load[0].traction") ->
  /// canonical value text (numbers in shortest round-trip form, so 7e10 and 70000000000.0
  /// agree; comments, layout and key order do not matter). A run's checkpoint stores it to
  /// refuse resuming a different problem (io/checkpoint.hpp).
  std::map<std::string, std::string> problem_settings;

  /// 2 or 3, the body's dimension.
  [[nodiscard]] int dim() const { return body.shape.dim(); }
  /// The [cost] of a study; throws InvalidInput naming the accepted kinds when the case has none.
  [[nodiscard]] const study::CostDefinition& required_cost() const;
  /// The [identification] table; throws InvalidInput when the case has none.
  [[nodiscard]] const IdentificationSetup& required_identification() const;
};

}  // namespace frictopt::io
