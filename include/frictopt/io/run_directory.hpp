// SPDX-License-Identifier: MIT
// The output directory of a frictopt command, owned in one place: creating it, refusing to
// mix runs, clearing a previous run (--force), resuming (--resume), the lock against a second
// concurrent process, the history, the checkpoint, the VTK series and the summary. Used by
// `optimize`, `certify`, `identify` and `solve`. The rules are in docs/case-format.md, "Run
// directories".
//
// It lives in io, not study: it is about files and their formats (CSV, JSON, VTK), which the
// numeric modules stay free of, and io already depends on study for the states it writes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/io/case_description.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/pvd_writer.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {

/// How a command opens its directory.
enum class RunOpening {
  kOutput,    ///< solve, identify: created if missing; our files in it are replaced
  kNewRun,    ///< optimize: created if missing; refused if it holds frictopt outputs already
  kForce,     ///< optimize --force: a previous run's files are removed first (only ours)
  kResume,    ///< optimize --resume: continue the run (checkpoint.json and case.toml required)
  kExisting,  ///< certify: an existing run (case.toml and final_design.json required)
};

class RunDirectory {
 public:
  static constexpr std::string_view kLockFile = ".frictopt.lock";
  static constexpr std::string_view kCaseCopy = "case.toml";
  static constexpr std::string_view kCheckpoint = "checkpoint.json";
  static constexpr std::string_view kHistory = "history.csv";
  static constexpr std::string_view kSummary = "summary.json";
  static constexpr std::string_view kFinalDesign = "final_design.json";
  static constexpr std::string_view kCertificate = "certificate.json";

  /// Opens `path` for a command and locks it for the object's lifetime (flock on
  /// PATH/.frictopt.lock; a second process gets InvalidInput "... is in use by frictopt
  /// process N"). `case_argument` is the case file the command was given (empty for
  /// certify); it is never removed. Throws InvalidInput when the opening is refused: a run
  /// exists (kNewRun), a foreign entry is present (kForce: the message lists them, nothing is
  /// removed), no run to resume (kResume), not a run (kExisting), or the path is not a
  /// directory. std::filesystem errors (permissions) propagate.
  RunDirectory(std::filesystem::path path, RunOpening opening, std::filesystem::path case_argument = {});
  ~RunDirectory();
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// The case file the command was given (empty for certify).
  [[nodiscard]] const std::filesystem::path& case_argument() const { return case_argument_; }
  [[nodiscard]] std::filesystem::path file(std::string_view name) const { return path_ / name; }

  /// True for the names frictopt writes into a run directory: the fixed names above, fit.csv,
  /// ceres_report.txt, measurements.csv, and for each name N of `names` N.pvd, N.vtu,
  /// N_contact.csv, N_iterK.vtu (K four or more digits) and the shape export's N_design.step,
  /// N_optimized.msh and N_optimized.stl, and our temporaries
  /// ".<one of these>.XXXXXX.tmp". `pictures` (viz/render_run.py) counts when it holds only
  /// .png files. A symbolic link or special file is never ours.
  [[nodiscard]] static bool is_frictopt_output(const std::filesystem::path& entry,
                                               const std::vector<std::string>& names);

  /// The case the run solves: copies `case_argument` to PATH/case.toml (kNewRun, kForce) and
  /// returns the path to load; on kResume and kExisting the run's own copy.
  /// A case.toml already in a directory that holds no run (no checkpoint.json, history.csv or
  /// final_design.json) is someone's case file: refused (InvalidInput), never replaced, unless
  /// it is the very copy this run would write.
  [[nodiscard]] std::filesystem::path store_case();
  /// The same for a case given as TOML text (the Python module): `origin` is the path its
  /// relative file names resolve against (case_copy_text), so the copy is the CLI's.
  void store_case_text(const std::string& text, const std::filesystem::path& origin);

  /// certify: refuses (InvalidInput naming the changes) when the run's checkpoint holds another
  /// fingerprint than `current` (case.toml edited after the run); no checkpoint: no check.
  void check_run_fingerprint(const CaseFingerprint& current) const;

  /// kResume: refuses (InvalidInput naming every setting that changed) when the case argument
  /// defines another problem than the run's case.toml (`run_case`), or when `current` (the
  /// fingerprint of run_case and its mesh) differs from the checkpoint's. Only [optimization]
  /// and [output] may change between resumes.
  void check_resume(const CaseDescription& run_case, const RunCheckpoint& checkpoint,
                    const CaseFingerprint& current) const;

  /// The history CSV: a new file, or on kResume the existing one cut back to the rows of
  /// iterations <= `keep_through_iteration` (later rows belong to an iteration the
  /// checkpoint does not hold; a damaged last row — an interrupted write — is dropped with a
  /// note in `notes`; a damaged row before it is refused: a row with control characters (NUL
  /// bytes), of the wrong width, out of the order 1, 2, 3, ... (duplicated or copied rows), rows
  /// ending before the checkpoint's iteration, or — given `center_value`, the checkpoint's Θ —
  /// a theta at that iteration other than the checkpoint's).
  [[nodiscard]] CsvWriter open_history(std::vector<std::string> header, int keep_through_iteration,
                                       std::vector<std::string>& notes,
                                       std::optional<double> center_value = std::nullopt);

  [[nodiscard]] RunCheckpoint read_checkpoint() const;
  void write_checkpoint(const RunCheckpoint& checkpoint) const;

  /// The VTK series `name`.pvd: on kResume rebuilt from the files name_iterK.vtu with
  /// K <= `through_iteration` (other files are left alone and reported in `notes`).
  void start_series(const std::string& name, int through_iteration, std::vector<std::string>& notes);
  /// Writes name_iterK.vtu through `write_vtu(path)` and rewrites the .pvd.
  void add_to_series(int iteration, const std::function<void(const std::filesystem::path&)>& write_vtu);
  [[nodiscard]] bool series_has(int iteration) const;

  void write_json_file(std::string_view name, const JsonValue& json) const;
  void write_text_file(std::string_view name, std::string_view text) const;

 private:
  void lock();
  void clear_previous_run();
  [[nodiscard]] bool is_own_case_copy() const;
  void require_case_copy_is_ours(const std::filesystem::path& copy) const;
  [[nodiscard]] std::vector<std::string> known_names() const;

  std::filesystem::path path_;
  RunOpening opening_;
  std::filesystem::path case_argument_;
  int lock_fd_ = -1;
  std::string series_name_;
  std::vector<PvdEntry> series_;
};

/// The fingerprint of a case and the mesh of its body (checkpoint.hpp).
[[nodiscard]] CaseFingerprint fingerprint_of(const CaseDescription& description, const study::ElasticBody& body);

/// The text RunDirectory::store_case writes for the case at `case_path`: the case as written,
/// except that a relative `[mesh] file` is made absolute (the copy lives elsewhere).
[[nodiscard]] std::string case_copy_text(const std::string& text, const std::filesystem::path& case_path);

}  // namespace frictopt::io
