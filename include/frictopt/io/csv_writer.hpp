// SPDX-License-Identifier: MIT
// CSV history files (one row per iteration) that survive an interrupted run: every row is
// flushed to the operating system as soon as it is written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace frictopt::io {

/// One CSV field: an integer, a real number or text.
using CsvValue = std::variant<std::int64_t, double, std::string>;

/// Writes a CSV file (RFC 4180: comma-separated, text quoted when it holds a comma, quote or
/// line break) with a header line. Reals are written in the shortest form that reads back as
/// the same double; NaN and infinities as nan, inf, -inf (what numpy and pandas read).
/// Not thread-safe; one writer per file.
class CsvWriter {
 public:
  enum class Mode {
    kTruncate,  ///< start a new file, rows flushed as they come (a run's history)
    kAppend,    ///< continue an existing file whose header must equal `header`
    /// A whole table: the rows are kept in memory and `finish()` replaces `path` atomically
    /// (atomic_file.hpp), so a failed write (a full disk) leaves the previous file as it was.
    kReplace
  };

  /// Opens `path` and, unless appending to a non-empty file, writes and flushes the header.
  /// Throws InvalidInput if the header is empty or has an empty or duplicate column name, or
  /// (kAppend) the existing header differs; FileSystemError if the file cannot be opened.
  CsvWriter(const std::filesystem::path& path, std::vector<std::string> header,
            Mode mode = Mode::kTruncate);

  /// Appends one row and flushes it. Throws InvalidInput if the row's length differs from
  /// the header's, FileSystemError if the write fails.
  void write_row(std::span<const CsvValue> row);
  void write_row(std::initializer_list<CsvValue> row) {
    write_row(std::span<const CsvValue>(row.begin(), row.size()));
  }
  /// Convenience for all-real rows.
  void write_row(std::span<const double> row);
  /// kReplace: writes the table to `path` (FileSystemError when the system refuses; the
  /// previous file is then kept). Without it nothing is written. No-op in the other modes.
  void finish();

  [[nodiscard]] const std::vector<std::string>& header() const { return header_; }
  [[nodiscard]] std::int64_t rows_written() const { return rows_written_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  void write_line(const std::string& line);

  std::filesystem::path path_;
  std::vector<std::string> header_;
  std::ofstream out_;
  Mode mode_ = Mode::kTruncate;
  std::string buffer_;  // kReplace: the table so far
  std::int64_t rows_written_ = 0;
};

}  // namespace frictopt::io
