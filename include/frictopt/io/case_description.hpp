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
#include <vector>

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

/// The measurements and loads of one experiment of an identification (docs/identification.md,
/// "Several experiments"): an [[identification.experiment]] table, or the [identification] table
/// itself when it has none (the case's loads, no turn).
struct IdentificationExperimentSetup {
  std::string name = "case";
  /// Scale factors of the case's [[load]], [[dirichlet]] and [[force]] tables: one per table, or a
  /// single one for every table; empty: 1 (study::IdentificationExperiment).
  std::vector<double> load_scale, dirichlet_scale, force_scale;
  double orientation = 0.0;  ///< [rad]: the friction law turned by it in the contact plane
  /// A measurement CSV, resolved against the case file's directory; absent: inline rows only.
  std::optional<std::filesystem::path> measurements;
  /// [[...measurement]] rows, in file order (labels "case.toml:LINE: identification.measurement[k]").
  std::vector<study::Measurement> inline_measurements;
  /// True when the table gives measurements (a file or inline rows).
  [[nodiscard]] bool has_measurements() const { return measurements.has_value() || !inline_measurements.empty(); }
};

/// [identification]: identify friction coefficients (and E) from measurements (docs/identification.md).
struct IdentificationSetup {
  /// The experiments: the [[identification.experiment]] tables in order, or one implicit experiment
  /// (the case's loads; `explicit_experiments` false) holding [identification]'s own `measurements`
  /// file and [[identification.measurement]] rows — which may be none (Python passes a list).
  std::vector<IdentificationExperimentSetup> experiments{1};
  bool explicit_experiments = false;
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
