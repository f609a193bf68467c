// SPDX-License-Identifier: MIT
// See run_directory.hpp. The layout and the resume rules are those of
// apps/frictopt/optimize_command.cpp.
#include "run_directory.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/state_output.hpp"

namespace frictopt::python {

namespace fs = std::filesystem;

namespace {

bool holds_run(const fs::path& dir) { return fs::exists(dir / "checkpoint.json") || fs::exists(dir / "history.csv"); }

std::vector<std::string> split_csv(const std::string& text) {
  std::vector<std::string> fields;
  std::stringstream stream(text);
  for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
  return fields;
}

// The files a run writes: the only ones `force` may remove.
bool is_run_file(const fs::path& file) {
  static const std::vector<std::string> fixed = {"case.toml",         "history.csv",  "checkpoint.json",
                                                 "final_design.json", "summary.json", "certificate.json"};
  const std::string name = file.filename().string();
  if (std::find(fixed.begin(), fixed.end(), name) != fixed.end()) return true;
  const std::string ext = file.extension().string();
  return (ext == ".vtu" && name.find("_iter") != std::string::npos) || ext == ".pvd";
}

}  // namespace

RunDirectory::RunDirectory(fs::path directory, bool resume, bool force)
    : directory_(std::move(directory)), resume_(resume) {
  const bool existing = holds_run(directory_);
  if (resume && !existing)
    throw InvalidInput(fmt::format("resume: {} holds no run to resume (no checkpoint.json)", directory_.string()));
  if (!resume && existing && !force)
    throw InvalidInput(fmt::format("{} already holds a run; pass resume=True to continue it or force=True to replace it",
                                   directory_.string()));
  if (!resume && existing && force)
    for (const auto& entry : fs::directory_iterator(directory_))
      if (entry.is_regular_file() && is_run_file(entry.path())) fs::remove(entry.path());
  fs::create_directories(directory_);
}

void RunDirectory::start(const std::string& case_toml, const std::string& name, bool write_vtk, int every) {
  name_ = name;
  write_vtk_ = write_vtk;
  every_ = every;
  if (!resume_) {
    std::ofstream(case_path()) << case_toml;
  } else {
    checkpoint_ = io::read_checkpoint(directory_ / "checkpoint.json");
    // The series written so far, and the counters of the interrupted run (its history's last row).
    for (const auto& entry : fs::directory_iterator(directory_)) {
      const std::string file = entry.path().filename().string();
      if (file.rfind(name_ + "_iter", 0) == 0 && entry.path().extension() == ".vtu")
        series_.push_back({std::stod(file.substr(name_.size() + 5, 4)), entry.path().filename()});
    }
    std::sort(series_.begin(), series_.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
    std::ifstream previous(directory_ / "history.csv");
    std::string line, header, last;
    std::getline(previous, header);
    while (std::getline(previous, line))
      if (!line.empty()) last = line;
    const auto names = split_csv(header), values = split_csv(last);
    for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) {
      if (names[k] == "elapsed_seconds") elapsed_offset_ = std::stod(values[k]);
      if (names[k] == "state_solves") solves_offset_ = std::stoll(values[k]);
    }
  }
  history_ = std::make_unique<io::CsvWriter>(directory_ / "history.csv", history_columns(),
                                             resume_ ? io::CsvWriter::Mode::kAppend : io::CsvWriter::Mode::kTruncate);
}

const std::vector<std::string>& RunDirectory::history_columns() {
  static const std::vector<std::string> columns = {
      "iteration",   "evaluations",        "step",          "theta",       "t",
      "stationarity_relative", "aggregate_error_relative", "bundle_size", "serious_steps", "null_steps",
      "state_solves", "coulomb_iterations", "qp_iterations", "weak_nodes", "state_seconds",
      "subgradient_seconds", "elapsed_seconds"};
  return columns;
}

std::vector<io::CsvValue> RunDirectory::history_row(const study::OptimizationProgress& p, std::int64_t solves_offset,
                                                    double elapsed_offset) {
  const auto& m = p.method;
  return {static_cast<std::int64_t>(m.iteration), static_cast<std::int64_t>(m.evaluations),
          std::string(optim::to_string(m.step)), m.f, m.t, m.stationarity, m.aggregate_error,
          static_cast<std::int64_t>(m.bundle.size()), static_cast<std::int64_t>(m.serious_steps),
          static_cast<std::int64_t>(m.null_steps), solves_offset + static_cast<std::int64_t>(p.state_solves),
          static_cast<std::int64_t>(p.center.contact.iterations), static_cast<std::int64_t>(p.center.contact.qp_iterations),
          static_cast<std::int64_t>(p.center.index_sets.num_weak_nodes()), p.center.state_seconds,
          p.center.subgradient_seconds, elapsed_offset + p.elapsed_seconds};
}

void RunDirectory::record(const study::OptimizationProgress& p, const study::ElasticBody& body,
                          study::ShapeOracle& oracle) {
  history_->write_row(history_row(p, solves_offset_, elapsed_offset_));
  io::write_json(directory_ / "checkpoint.json", io::checkpoint_to_json(p.method));
  if (p.method.iteration % every_ == 0) write_design_vtu(p.method.iteration, p.method.x, body, oracle);
}

void RunDirectory::write_design_vtu(int iteration, const Eigen::VectorXd& alpha, const study::ElasticBody& body,
                                    study::ShapeOracle& oracle) {
  if (!write_vtk_) return;
  const fs::path file = fmt::format("{}_iter{:04d}.vtu", name_, iteration);
  io::write_state_vtu(directory_ / file, body, oracle.state(alpha));  // a recent state: no new solve
  series_.push_back({static_cast<double>(iteration), file});
  io::write_pvd(directory_ / (name_ + ".pvd"), series_);
}

void RunDirectory::finish(const optim::BundleTrust::Summary& summary, const io::JsonValue& json,
                          const study::ElasticBody& body, study::ShapeOracle& oracle) {
  if (series_.empty() || series_.back().time != summary.iterations)
    write_design_vtu(summary.iterations, summary.x, body, oracle);
  io::JsonValue design = io::JsonValue::object();
  design["alpha"] = summary.x;
  io::write_json(directory_ / "final_design.json", design);
  io::write_json(directory_ / "summary.json", json);
}

}  // namespace frictopt::python
