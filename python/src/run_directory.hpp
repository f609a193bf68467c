// SPDX-License-Identifier: MIT
// The files of an optimization run directory, in the CLI's layout (`frictopt optimize`):
// case.toml, history.csv, checkpoint.json, <name>_iterNNNN.vtu + <name>.pvd, final_design.json,
// summary.json — so `frictopt certify DIR` and `frictopt optimize --resume` work on runs started
// from Python and vice versa. All file handling of python's optimize is here, in one place, so
// that it can move onto the project's run-directory object once that exists.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/pvd_writer.hpp"
#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace frictopt::python {

class RunDirectory {
 public:
  /// Opens `directory` for a fresh run or, with `resume`, for continuing the run it holds.
  /// Throws InvalidInput when resuming a directory without a run, or when starting a fresh run
  /// in a directory that holds one without `force` (with `force` the previous run's files —
  /// and only those — are removed).
  RunDirectory(std::filesystem::path directory, bool resume, bool force);

  const std::filesystem::path& path() const { return directory_; }
  bool resuming() const { return resume_; }
  /// DIR/case.toml: the case the run solves (written by start(), read on resume).
  std::filesystem::path case_path() const { return directory_ / "case.toml"; }

  /// A fresh run: stores the case text as DIR/case.toml and truncates the history.
  /// A resume: reads the checkpoint and the counters of the history's last row.
  void start(const std::string& case_toml, const std::string& name, bool write_vtk, int every);
  /// The method's state to resume from (resume only).
  const optim::BundleTrust::IterationSummary* checkpoint() const { return checkpoint_ ? &*checkpoint_ : nullptr; }
  double elapsed_offset() const { return elapsed_offset_; }
  std::int64_t solves_offset() const { return solves_offset_; }

  /// After an outer iteration: a history.csv row (flushed), the checkpoint (atomic replace)
  /// and, every `every` iterations, the state of the iterate as VTK.
  void record(const study::OptimizationProgress& progress, const study::ElasticBody& body, study::ShapeOracle& oracle);
  /// The design's VTK file of iteration `iteration` and the updated .pvd series.
  void write_design_vtu(int iteration, const Eigen::VectorXd& alpha, const study::ElasticBody& body,
                        study::ShapeOracle& oracle);
  /// final_design.json, summary.json and the last iterate's VTK file if not written yet.
  void finish(const optim::BundleTrust::Summary& summary, const io::JsonValue& json, const study::ElasticBody& body,
              study::ShapeOracle& oracle);

  /// The columns of history.csv (also the fields of the progress object given to callbacks).
  static const std::vector<std::string>& history_columns();
  /// One history row; `solves_offset`/`elapsed_offset` continue the counters of a resumed run.
  static std::vector<io::CsvValue> history_row(const study::OptimizationProgress& p, std::int64_t solves_offset,
                                               double elapsed_offset);

 private:
  std::filesystem::path directory_;
  bool resume_ = false;
  std::string name_;
  bool write_vtk_ = true;
  int every_ = 1;
  std::optional<optim::BundleTrust::IterationSummary> checkpoint_;
  double elapsed_offset_ = 0.0;
  std::int64_t solves_offset_ = 0;
  std::unique_ptr<io::CsvWriter> history_;
  std::vector<io::PvdEntry> series_;
};

}  // namespace frictopt::python
