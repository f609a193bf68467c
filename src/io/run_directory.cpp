// SPDX-License-Identifier: MIT
#include "frictopt/io/run_directory.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "atomic_file.hpp"
#include "input_file.hpp"
#include "frictopt/core/validation.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io {
namespace {

namespace fs = std::filesystem;

// Fixed names of the files frictopt's commands write into their directories.
constexpr std::string_view kFixedNames[] = {
    RunDirectory::kLockFile, RunDirectory::kCaseCopy, RunDirectory::kCheckpoint, RunDirectory::kHistory,
    RunDirectory::kSummary,  RunDirectory::kFinalDesign, RunDirectory::kCertificate, "fit.csv",
    "ceres_report.txt",      "measurements.csv", "tribometer_ramp.csv", "tribometer_polar.csv",
    "tribometer_law.csv"};

// K of "<name>_iterK.vtu" (four or more digits), or nullopt.
std::optional<int> series_index(std::string_view file, std::string_view name) {
  const std::string prefix = std::string(name) + "_iter";
  if (!file.starts_with(prefix) || !file.ends_with(".vtu")) return std::nullopt;
  const std::string_view digits = file.substr(prefix.size(), file.size() - prefix.size() - 4);
  if (digits.size() < 4 || digits.find_first_not_of("0123456789") != std::string_view::npos) return std::nullopt;
  int k = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), k);
  if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return k;
}

bool is_output_name(std::string_view file, const std::vector<std::string>& names) {
  for (std::string_view fixed : kFixedNames)
    if (file == fixed) return true;
  for (const std::string& n : names) {
    if (n.empty()) continue;
    if (file == n + ".pvd" || file == n + ".vtu" || file == n + "_contact.csv") return true;
    if (file == n + "_design.step" || file == n + "_optimized.msh" || file == n + "_optimized.stl") return true;
    if (series_index(file, n)) return true;
  }
  return false;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return !a.empty() && !b.empty() && fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

std::string list_entries(const std::vector<std::string>& entries) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(entries.size(), 10);
  for (std::size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + entries[i];
  if (entries.size() > shown) out += fmt::format(" and {} more", entries.size() - shown);
  return out;
}

// output.name of a case file, or empty when it cannot be parsed (then only the fixed names
// and the other names count as ours).
std::string output_name_of(const fs::path& case_path) {
  try {
    return load_case(case_path).output.name;
  } catch (const InvalidInput&) {
    return {};
  }
}

// Whether `directory` holds a run of frictopt's: the files only a run writes (a case.toml
// alone is anyone's case file).
bool holds_run(const fs::path& directory) {
  std::error_code ec;
  for (std::string_view name : {RunDirectory::kCheckpoint, RunDirectory::kHistory, RunDirectory::kFinalDesign})
    if (fs::exists(directory / name, ec)) return true;
  return false;
}

std::string read_whole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

bool RunDirectory::is_frictopt_output(const fs::path& entry, const std::vector<std::string>& names) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(entry, ec);
  const std::string file = entry.filename().string();
  if (status.type() == fs::file_type::directory) {
    if (file != "pictures") return false;
    for (const auto& inner : fs::directory_iterator(entry, ec))
      if (inner.path().extension() != ".png" || !inner.is_regular_file() || inner.is_symlink()) return false;
    return !ec;
  }
  if (status.type() != fs::file_type::regular) return false;
  // ".<output>.XXXXXX.tmp": a temporary of ours left by an interrupted write (atomic_file.hpp).
  if (file.size() > 12 && file.front() == '.' && file.ends_with(".tmp")) {
    const std::string inner = file.substr(1, file.size() - 1 - 4);
    const auto dot = inner.rfind('.');
    if (dot != std::string::npos && inner.size() - dot - 1 == 6 && is_output_name(inner.substr(0, dot), names))
      return true;
  }
  return is_output_name(file, names);
}

RunDirectory::RunDirectory(fs::path path, RunOpening opening, fs::path case_argument)
    : path_(std::move(path)), opening_(opening), case_argument_(std::move(case_argument)) {
  if (path_.empty()) path_ = ".";
  std::error_code ec;
  const fs::file_status status = fs::status(path_, ec);
  const bool exists = status.type() != fs::file_type::not_found && !ec;
  if (exists && status.type() != fs::file_type::directory)
    throw InvalidInput(fmt::format("{}: exists and is not a directory; expected an output directory", path_.string()));
  if (!case_argument_.empty() && opening_ != RunOpening::kExisting && !fs::is_regular_file(case_argument_, ec))
    throw InvalidInput(fmt::format("{}: the case file does not exist (or is not a regular file)",
                                   case_argument_.string()));
  const bool has_run = exists && (fs::exists(file(kCheckpoint), ec) || fs::exists(file(kHistory), ec));
  switch (opening_) {
    case RunOpening::kResume:
      if (!exists || !fs::exists(file(kCheckpoint), ec))
        throw InvalidInput(fmt::format("--resume: {} holds no run to resume (no {})", path_.string(), kCheckpoint));
      if (!fs::is_regular_file(file(kCaseCopy), ec))
        throw InvalidInput(fmt::format("--resume: {} is missing; it is the case the run solves", file(kCaseCopy).string()));
      break;
    case RunOpening::kExisting:
      if (!exists) throw InvalidInput(path_.string() + ": the run directory does not exist");
      for (std::string_view name : {kCaseCopy, kFinalDesign})
        if (!fs::is_regular_file(file(name), ec))
          throw InvalidInput(fmt::format("{}: missing; expected a run directory written by `frictopt optimize`",
                                         file(name).string()));
      break;
    case RunOpening::kNewRun:
      if (has_run)
        throw InvalidInput(fmt::format("{} already holds a run; pass --resume to continue it or --force to replace it",
                                       path_.string()));
      // Before anything is created in it: a case.toml there that is not ours stays untouched.
      if (exists && !case_argument_.empty() && !same_file(case_argument_, file(kCaseCopy)))
        require_case_copy_is_ours(file(kCaseCopy));
      break;
    case RunOpening::kForce:
    case RunOpening::kOutput:
      break;
  }
  fs::create_directories(path_);
  lock();
  if (opening_ == RunOpening::kForce) {
    // A refused --force must release the lock: the destructor does not run for a throwing
    // constructor, and a process that goes on (the Python module) would keep the directory locked.
    try {
      clear_previous_run();
    } catch (...) {
      ::close(lock_fd_);
      lock_fd_ = -1;
      throw;
    }
  }
}

RunDirectory::~RunDirectory() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the flock; the file stays (harmless, ours)
}

void RunDirectory::lock() {
  const fs::path lock_path = file(kLockFile);
  detail::require_regular_output(lock_path);
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (lock_fd_ < 0) {
    const int error = errno;  // a read-only file system, no permission: exit 5, not bad input
    throw FileSystemError(fmt::format("{}: cannot create the lock file: {}", lock_path.string(), std::strerror(error)),
                          lock_path, error);
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char pid[32] = {};
    const ssize_t n = ::pread(lock_fd_, pid, sizeof pid - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (error == EWOULDBLOCK)
      throw InvalidInput(fmt::format("{} is in use by another frictopt process{} (lock {}); wait for it to end or "
                                     "choose another output directory",
                                     path_.string(), n > 0 ? fmt::format(" (pid {})", std::string(pid, static_cast<std::size_t>(n))) : "",
                                     lock_path.string()));
    throw FileSystemError(fmt::format("{}: cannot lock: {}", lock_path.string(), std::strerror(error)), lock_path,
                          error);
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(lock_fd_, 0) == 0 && ::pwrite(lock_fd_, pid.data(), pid.size(), 0) < 0) {
    // the pid is only for the message of a second process
  }
}

std::vector<std::string> RunDirectory::known_names() const {
  std::vector<std::string> names;
  if (!case_argument_.empty()) names.push_back(output_name_of(case_argument_));
  std::error_code ec;
  if (fs::is_regular_file(file(kCaseCopy), ec)) names.push_back(output_name_of(file(kCaseCopy)));
  return names;
}

void RunDirectory::clear_previous_run() {
  const std::vector<std::string> names = known_names();
  std::vector<fs::path> ours;
  std::vector<std::string> foreign;
  // case.toml is the run's copy only in a directory that holds a run, or when it is the very
  // copy this run would write; otherwise it is someone's case file and is not removed.
  const bool run_present = holds_run(path_);
  for (const auto& entry : fs::directory_iterator(path_)) {
    const std::string file_name = entry.path().filename().string();
    if (file_name == kLockFile || same_file(entry.path(), case_argument_)) continue;
    const bool foreign_case = file_name == kCaseCopy && !run_present && !is_own_case_copy();
    if (!foreign_case && is_frictopt_output(entry.path(), names))
      ours.push_back(entry.path());
    else
      foreign.push_back(file_name + (entry.is_directory() && !entry.is_symlink() ? "/" : ""));
  }
  std::sort(foreign.begin(), foreign.end());
  if (!foreign.empty())
    throw InvalidInput(fmt::format("--force: {} holds {} entr{} frictopt did not write ({}); --force removes only "
                                   "frictopt's own outputs, so nothing was removed: choose an empty or new directory, "
                                   "or move those entries away",
                                   path_.string(), foreign.size(), foreign.size() == 1 ? "y" : "ies",
                                   list_entries(foreign)));
  for (const fs::path& p : ours) fs::remove_all(p);
}

namespace {

// TOML basic string of a path (quotes and backslashes escaped).
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

}  // namespace

std::string case_copy_text(const std::string& text, const fs::path& case_path) {
  // The copy lives in the run directory, so a mesh file named relative to the user's case
  // ([mesh] file) is named absolutely in it; `certify RUN_DIR` and `--resume` then
  // read the same mesh. Only that value's text changes (the rest of the file stays as written);
  // a case that does not parse is copied as it is (its parse reports the error).
  toml::table root;
  try {
    root = toml::parse(text);
  } catch (const toml::parse_error&) {
    return text;
  }
  const toml::node* node = root.at_path("mesh.file").node();
  const auto* value = node != nullptr ? node->as_string() : nullptr;
  if (value == nullptr || fs::path(value->get()).is_absolute() || node->source().begin.line == 0) return text;
  const fs::path absolute = fs::absolute(case_path.parent_path() / value->get()).lexically_normal();
  // Replace the value on its line (a TOML string value is one line unless multi-line, which a
  // path never needs; a multi-line string is left as it is).
  std::size_t begin = 0;
  for (std::uint32_t line = 1; line < node->source().begin.line; ++line) {
    begin = text.find('\n', begin);
    if (begin == std::string::npos) return text;
    ++begin;
  }
  const std::size_t column = begin + node->source().begin.column - 1;
  const std::size_t end_line = text.find('\n', column);
  const std::string line_text = text.substr(column, end_line == std::string::npos ? std::string::npos : end_line - column);
  const char quote = line_text.empty() ? '\0' : line_text.front();
  if (quote != '"' && quote != '\'') return text;
  const std::size_t close = line_text.find(quote, 1);
  if (close == std::string::npos || line_text.compare(0, 3, std::string(3, quote)) == 0) return text;
  return text.substr(0, column) + toml_string(absolute.string()) + text.substr(column + close + 1);
}

bool RunDirectory::is_own_case_copy() const {
  std::error_code ec;
  const fs::path copy = file(kCaseCopy);
  if (case_argument_.empty() || !fs::is_regular_file(copy, ec)) return false;
  return read_whole(copy) == case_copy_text(read_whole(case_argument_), case_argument_);
}

void RunDirectory::require_case_copy_is_ours(const fs::path& copy) const {
  // A case.toml in a directory without a run is someone's case file (the user's own, a
  // colleague's): it is never replaced. The same text as the copy would hold is no loss.
  std::error_code ec;
  if (fs::symlink_status(copy, ec).type() == fs::file_type::not_found || holds_run(path_)) return;
  if (case_argument_.empty() || !is_own_case_copy())
    throw InvalidInput(fmt::format("{}: exists and {} holds no frictopt run (no {}, {} or {}); frictopt does not "
                                   "replace a case file it did not write: choose another output directory or move "
                                   "the file away",
                                   copy.string(), path_.string(), kCheckpoint, kHistory, kFinalDesign));
}

fs::path RunDirectory::store_case() {
  const fs::path copy = file(kCaseCopy);
  if (opening_ == RunOpening::kResume || opening_ == RunOpening::kExisting) return copy;
  if (case_argument_.empty()) throw InvalidInput("RunDirectory::store_case: no case argument");
  if (same_file(case_argument_, copy)) return copy;  // the case already lives there
  require_case_copy_is_ours(copy);
  detail::write_file_atomically(copy, case_copy_text(read_whole(case_argument_), case_argument_));
  return copy;
}

void RunDirectory::store_case_text(const std::string& text, const fs::path& origin) {
  const fs::path copy = file(kCaseCopy);
  std::error_code ec;
  detail::require_regular_output(copy);  // a FIFO there would block the comparison below
  if (fs::exists(copy, ec) && !holds_run(path_) && read_whole(copy) != case_copy_text(text, origin))
    throw InvalidInput(fmt::format("{}: exists and {} holds no frictopt run (no {}, {} or {}); frictopt does not "
                                   "replace a case file it did not write: choose another output directory or move "
                                   "the file away",
                                   copy.string(), path_.string(), kCheckpoint, kHistory, kFinalDesign));
  detail::write_file_atomically(copy, case_copy_text(text, origin));
}

void RunDirectory::check_run_fingerprint(const CaseFingerprint& current) const {
  std::error_code ec;
  if (!fs::exists(file(kCheckpoint), ec)) return;  // a run without checkpoint: nothing to compare
  const RunCheckpoint checkpoint = read_checkpoint();
  const std::vector<std::string> changes = current.differences_from(checkpoint.fingerprint);
  if (!changes.empty())
    throw InvalidInput(fmt::format("{}: no longer defines the problem of the run (its checkpoint {}; checkpoint -> "
                                   "now): {}; the final design belongs to the run's problem: undo the edit, or "
                                   "certify the design with a case of its own",
                                   file(kCaseCopy).string(), file(kCheckpoint).string(), list_entries(changes)));
}

void RunDirectory::check_resume(const CaseDescription& run_case, const RunCheckpoint& checkpoint,
                                const CaseFingerprint& current) const {
  if (!case_argument_.empty() && !same_file(case_argument_, file(kCaseCopy))) {
    const CaseDescription argument = load_case(case_argument_);
    CaseFingerprint given, run;
    given.dim = argument.dim();
    given.settings = argument.problem_settings;
    run.dim = run_case.dim();
    run.settings = run_case.problem_settings;
    given.case_hash = run.case_hash = 0;
    const std::vector<std::string> changes = given.differences_from(run);
    if (!changes.empty())
      throw InvalidInput(fmt::format("--resume: the case argument {} is not the case of the run in {} ({}): {}; "
                                     "resume with the run's case (its copy is {}) or start a new run",
                                     case_argument_.string(), path_.string(), file(kCaseCopy).string(),
                                     list_entries(changes), file(kCaseCopy).string()));
  }
  const std::vector<std::string> changes = current.differences_from(checkpoint.fingerprint);
  if (!changes.empty())
    throw InvalidInput(fmt::format("--resume: {} no longer defines the problem of the checkpoint {} (checkpoint -> "
                                   "now): {}; a run continues one problem only (only [optimization] and [output] "
                                   "may change): undo the edit or start a new run",
                                   file(kCaseCopy).string(), file(kCheckpoint).string(), list_entries(changes)));
}

CsvWriter RunDirectory::open_history(std::vector<std::string> header, int keep_through_iteration,
                                     std::vector<std::string>& notes, std::optional<double> center_value) {
  const fs::path history = file(kHistory);
  if (opening_ != RunOpening::kResume) return CsvWriter(history, std::move(header), CsvWriter::Mode::kTruncate);
  detail::require_regular_output(history);
  std::error_code exists_ec;
  // A history holds one short row per iteration: 64 MiB is far beyond any run's (and bounds
  // what a damaged file can make the resume read).
  const std::string content = fs::exists(history, exists_ec)
                                  ? detail::read_input_file(history, "the history", std::size_t{64} << 20)
                                  : std::string();
  std::vector<std::string> lines;
  {
    std::istringstream in(content);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  const auto theta_column = std::find(header.begin(), header.end(), "theta") - header.begin();
  std::string kept;
  if (!lines.empty()) {
    kept = lines[0] + "\n";
    std::size_t last = lines.size();
    while (last > 1 && lines[last - 1].empty()) --last;
    int dropped = 0;
    int previous = 0;  // rows are iterations 1, 2, 3, ... (each once, in order)
    bool torn_last_row = false;
    for (std::size_t i = 1; i < last; ++i) {
      const std::string& row = lines[i];
      const std::string first = row.substr(0, row.find(','));
      int iteration = -1;
      const auto [end, ec] = std::from_chars(first.data(), first.data() + first.size(), iteration);
      // A row of ours is printable ASCII (numbers and step names): NUL bytes or other control
      // characters are damage, not data.
      const bool printable = std::all_of(row.begin(), row.end(), [](char ch) {
        return static_cast<unsigned char>(ch) >= 0x20 && static_cast<unsigned char>(ch) < 0x7f;
      });
      const bool complete = ec == std::errc() && end == first.data() + first.size() && printable &&
                            static_cast<std::size_t>(std::count(row.begin(), row.end(), ',')) + 1 == header.size();
      if (complete && iteration <= keep_through_iteration && iteration != previous + 1)
        throw InvalidInput(fmt::format("{}:{}: a row of iteration {} after iteration {}; expected iteration {} (a "
                                       "duplicated, copied or missing row; repair or remove the rows to resume)",
                                       history.string(), i + 1, iteration, previous, previous + 1));
      if (complete) previous = std::max(previous, iteration);
      if (complete && iteration == keep_through_iteration && center_value && theta_column < std::ssize(header)) {
        // The checkpoint's centre value is the theta of its iteration's row (both written from
        // the same number, in shortest round-trip form): two files that disagree were edited.
        std::string_view field = row;
        for (std::ptrdiff_t k = 0; k < theta_column; ++k) field.remove_prefix(field.find(',') + 1);
        field = field.substr(0, field.find(','));
        double theta = kNaN;
        const auto [theta_end, theta_ec] = std::from_chars(field.data(), field.data() + field.size(), theta);
        if (theta_ec != std::errc() || theta_end != field.data() + field.size() || theta != *center_value)
          throw InvalidInput(fmt::format("{}:{}: theta = {} at iteration {}, but the checkpoint {} holds Θ = {}; one "
                                         "of the two files was edited or damaged (a run resumes only from its own, "
                                         "consistent files)",
                                         history.string(), i + 1, detail::printable_excerpt(field, 30), iteration,
                                         file(kCheckpoint).string(), format_number(*center_value)));
      }
      if (!complete) {
        if (i + 1 == last) {
          torn_last_row = true;
          notes.push_back(fmt::format("{}:{}: the last row is incomplete (an interrupted write); dropped",
                                      history.string(), i + 1));
          continue;
        }
        throw InvalidInput(fmt::format("{}:{}: a damaged row \"{}\" before the last one; expected {} fields starting "
                                       "with the iteration (repair or remove the row to resume)",
                                       history.string(), i + 1, detail::printable_excerpt(row, 60), header.size()));
      }
      if (iteration > keep_through_iteration) {
        ++dropped;
        continue;
      }
      kept += row + "\n";
    }
    if (dropped > 0)
      notes.push_back(fmt::format("{}: {} row(s) after the checkpoint's iteration {} dropped (that work is redone)",
                                  history.string(), dropped, keep_through_iteration));
    if (previous < keep_through_iteration && !torn_last_row)
      throw InvalidInput(fmt::format("{}: the rows end at iteration {}; the checkpoint {} is at iteration {} (rows "
                                     "were removed; repair the history or start the run again with --force)",
                                     history.string(), previous, file(kCheckpoint).string(), keep_through_iteration));
  }
  detail::write_file_atomically(history, kept);
  return CsvWriter(history, std::move(header), CsvWriter::Mode::kAppend);
}

RunCheckpoint RunDirectory::read_checkpoint() const { return io::read_checkpoint(file(kCheckpoint)); }

void RunDirectory::write_checkpoint(const RunCheckpoint& checkpoint) const {
  write_json(file(kCheckpoint), checkpoint_to_json(checkpoint));
}

void RunDirectory::start_series(const std::string& name, int through_iteration, std::vector<std::string>& notes) {
  series_name_ = name;
  series_.clear();
  if (opening_ != RunOpening::kResume) return;
  std::vector<std::string> ignored;
  for (const auto& entry : fs::directory_iterator(path_)) {
    const std::string file_name = entry.path().filename().string();
    if (!file_name.starts_with(name + "_iter") || entry.path().extension() != ".vtu") continue;
    const std::optional<int> k = series_index(file_name, name);
    if (!k || !entry.is_regular_file() || entry.is_symlink()) {
      ignored.push_back(file_name);
    } else if (*k <= through_iteration) {
      series_.push_back({static_cast<double>(*k), entry.path().filename()});
    }
  }
  std::sort(series_.begin(), series_.end(), [](const PvdEntry& a, const PvdEntry& b) { return a.time < b.time; });
  std::sort(ignored.begin(), ignored.end());
  if (!ignored.empty())
    notes.push_back(fmt::format("{}: not part of the VTK series and left alone: {}", path_.string(),
                                list_entries(ignored)));
}

bool RunDirectory::series_has(int iteration) const {
  return std::any_of(series_.begin(), series_.end(),
                     [&](const PvdEntry& e) { return e.time == static_cast<double>(iteration); });
}

void RunDirectory::add_to_series(int iteration, const std::function<void(const fs::path&)>& write_vtu) {
  const fs::path vtu = fmt::format("{}_iter{:04d}.vtu", series_name_, iteration);
  write_vtu(path_ / vtu);
  series_.erase(std::remove_if(series_.begin(), series_.end(),
                               [&](const PvdEntry& e) { return e.time == static_cast<double>(iteration); }),
                series_.end());
  series_.push_back({static_cast<double>(iteration), vtu});
  std::sort(series_.begin(), series_.end(), [](const PvdEntry& a, const PvdEntry& b) { return a.time < b.time; });
  write_pvd(path_ / (series_name_ + ".pvd"), series_);
}

void RunDirectory::write_json_file(std::string_view name, const JsonValue& json) const { write_json(file(name), json); }

void RunDirectory::write_text_file(std::string_view name, std::string_view text) const {
  detail::write_file_atomically(file(name), text);
}

CaseFingerprint fingerprint_of(const CaseDescription& description, const study::ElasticBody& body) {
  CaseFingerprint f;
  f.dim = description.dim();
  f.settings = description.problem_settings;
  f.case_hash = hash_settings(f.settings);
  // The reference mesh X_ref = X(0): the case determines it, but a change of the mesh
  // generator between versions would otherwise go unnoticed.
  const Eigen::MatrixXd reference = body.mesh().positions(Eigen::VectorXd::Zero(body.definition().shape.num_controls()));
  f.num_nodes = reference.rows();
  f.mesh_hash = fnv1a64(reference.data(), static_cast<std::size_t>(reference.size()) * sizeof(double));
  // The rest of the mesh definition: the cells, every boundary group (name and facets) and the
  // bytes of the files an imported body was made from (the .msh, or the .geo and the files it
  // includes) — a .geo that swaps which curve is clamped leaves every node where it was.
  const mesh::Mesh& mesh = body.mesh();
  f.mesh_hash = fnv1a64(mesh.elements().data(), static_cast<std::size_t>(mesh.elements().size()) * sizeof(int), f.mesh_hash);
  for (const std::string& name : mesh.boundary_names()) {
    const mesh::BoundarySet& set = mesh.boundary(name);
    f.mesh_hash = fnv1a64(name.data(), name.size() + 1, f.mesh_hash);  // with its '\0': names stay apart
    f.mesh_hash = fnv1a64(set.facets.data(), static_cast<std::size_t>(set.facets.size()) * sizeof(int), f.mesh_hash);
  }
  if (const auto& imported = body.definition().imported_mesh)
    for (const std::filesystem::path& source : imported->sources) {
      std::ifstream in(source, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      f.mesh_hash = fnv1a64(bytes.data(), bytes.size(), f.mesh_hash);
    }
  return f;
}

}  // namespace frictopt::io
