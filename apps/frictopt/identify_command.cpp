// SPDX-License-Identifier: MIT
// `frictopt identify`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/io/measurements.hpp"
#include "frictopt/study/identification.hpp"
#include "frictopt/study/certificate.hpp"

namespace frictopt::app {

// frictopt identify: friction coefficients (and E) from the measurements named in the case's
// [identification] table (issue 7, docs/identification.md). Writes fit.csv (measured vs fitted
// per measurement), summary.json (estimates, covariance, correlation, Ceres report) and
// ceres_report.txt. With --generate-synthetic it instead writes measurements.csv: the rows of
// the case's measurement file with values from the case's own law plus N(0, σ²) noise (--seed).
int run_identify(const std::filesystem::path& case_path, const std::filesystem::path& out_dir, bool generate,
                 std::uint64_t seed, bool noise_free) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  if (!description.identification)
    throw InvalidInput(case_path.string() + ": identify needs an [identification] table (docs/identification.md)");
  const io::IdentificationSetup& setup = *description.identification;
  const std::vector<study::Measurement> measurements = io::read_measurements(setup.measurements);
  study::Identification identification(description.body, measurements, setup.options);
  const auto& names = identification.parameter_names();
  io::RunDirectory run(out_dir, io::RunOpening::kOutput, case_path);
  if (generate) {
    const Eigen::VectorXd truth = identification.case_parameters();
    const study::Identification::Prediction exact = identification.predict(truth);
    if (!exact.ok) {
      fmt::print("error: the model could not be evaluated at the case's parameters: {}\n", exact.message);
      return kExitNumericalFailure;
    }
    std::string truth_text;
    for (std::size_t k = 0; k < names.size(); ++k)
      truth_text += fmt::format("{}{} = {}", k ? ", " : "", names[k], truth(static_cast<Eigen::Index>(k)));
    const auto synthetic = study::synthetic_measurements(measurements, exact.values, seed, !noise_free);
    const auto path = run.file("measurements.csv");
    io::write_measurements(path, synthetic,
                           fmt::format("synthetic: frictopt identify {} --generate-synthetic --seed {}{}; {}; {}",
                                       case_path.filename().string(), seed, noise_free ? " --noise-free" : "",
                                       truth_text, exact.index_sets));
    fmt::print("{}\nwrote {} ({} measurements; truth {})\n", exact.contact.brief_report(), path.string(),
               synthetic.size(), truth_text);
    return kExitOk;
  }
  fmt::print("{}: {} measurements, {} parameters\n", case_path.string(), measurements.size(), names.size());
  const study::Identification::Summary s = identification.run();
  fmt::print("{}\n{}\n", s.ceres_brief_report, s.brief_report());
  fmt::print("{:<18} {:>14} {:>14} {:>12} {:>24}  {}\n", "parameter", "initial", "estimate", "std. dev.", "bounds",
             "identifiability");
  for (const auto& e : s.estimates)
    fmt::print("{:<18} {:>14.8g} {:>14.8g} {:>12} {:>24}  {}{}\n", e.name, e.initial, e.value,
               std::isnan(e.standard_deviation) ? std::string("-") : fmt::format("{:.3g}", e.standard_deviation),
               fmt::format("[{:g}, {:g}]", e.lower, e.upper), study::to_string(e.identifiability),
               e.note.empty() ? "" : ": " + e.note);
  if (s.correlation.size() && names.size() > 1) {
    fmt::print("correlation:\n");
    for (Eigen::Index a = 0; a < s.correlation.rows(); ++a) {
      std::string row;
      for (Eigen::Index b = 0; b < s.correlation.cols(); ++b)
        row += std::isnan(s.correlation(a, b)) ? fmt::format("{:>8}", "-") : fmt::format("{:>8.3f}", s.correlation(a, b));
      fmt::print("  {:<16}{}\n", names[static_cast<std::size_t>(a)], row);
    }
  }
  run.write_text_file("ceres_report.txt", s.ceres_full_report);
  if (s.predictions.size()) {
    io::CsvWriter fit(run.file("fit.csv"),
                      {"quantity", "node", "x1", "x2", "measured", "sigma", "fitted", "normalized_residual"});
    const Eigen::MatrixXd& xy = identification.contact_coordinates();
    const auto& ms = identification.measurements();
    for (std::size_t r = 0; r < ms.size(); ++r) {
      const auto& m = ms[r];
      const auto R = static_cast<Eigen::Index>(r);
      const double x1 = m.node >= 0 ? xy(m.node, 0) : kNaN;
      const double x2 = m.node >= 0 && xy.cols() > 1 ? xy(m.node, 1) : kNaN;
      fit.write_row({std::string(study::to_string(m.quantity)), std::int64_t{m.node}, x1, x2, m.value, m.sigma,
                     s.predictions(R), s.residuals(R)});
    }
  }
  io::JsonValue summary = io::JsonValue::object();
  summary["case"] = case_path.string();
  summary["command"] = "identify";
  io::add_members(summary, io::run_environment());
  io::add_members(summary, io::to_json(s));
  run.write_json_file(io::RunDirectory::kSummary, summary);
  fmt::print("wrote {}{}, {}\n", s.predictions.size() ? run.file("fit.csv").string() + ", " : std::string(),
             run.file(io::RunDirectory::kSummary).string(), run.file("ceres_report.txt").string());
  return s.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

}  // namespace frictopt::app
