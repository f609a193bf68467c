// SPDX-License-Identifier: MIT
#include "frictopt/io/csv_writer.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <set>

#include "atomic_file.hpp"
#include "input_file.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io {
namespace {

std::string quoted_if_needed(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string format_real(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::format("{}", x);  // shortest round-trip representation
}

std::string join(std::span<const std::string> fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line += quoted_if_needed(fields[i]);
  }
  return line;
}

}  // namespace

CsvWriter::CsvWriter(const std::filesystem::path& path, std::vector<std::string> header, Mode mode)
    : path_(path), header_(std::move(header)), mode_(mode) {
  if (header_.empty())
    throw InvalidInput(fmt::format("CsvWriter({}): the header is empty", path_.string()));
  std::set<std::string> seen;
  for (const std::string& name : header_)
    if (name.empty() || !seen.insert(name).second)
      throw InvalidInput(fmt::format("CsvWriter({}): column name '{}' is empty or repeated",
                                     path_.string(), name));
  const std::string header_line = join(header_);

  // Rows are appended in place (a history grows while the run goes), so this writer cannot
  // replace the file atomically; it still writes regular files only (atomic_file.hpp).
  detail::require_regular_output(path_);
  if (mode == Mode::kReplace) {
    write_line(header_line);
    return;
  }
  bool write_header = true;
  std::error_code ec;
  if (mode == Mode::kAppend && std::filesystem::exists(path_, ec) &&
      std::filesystem::file_size(path_, ec) > 0) {
    std::ifstream in(path_);
    std::string existing;
    std::getline(in, existing);
    if (!existing.empty() && existing.back() == '\r') existing.pop_back();
    if (existing != header_line)
      throw InvalidInput(
          fmt::format("CsvWriter({}): existing header '{}'; expected '{}' to "
                      "append",
                      path_.string(), detail::printable_excerpt(existing, 200), header_line));
    write_header = false;
  }
  out_.open(path_, mode == Mode::kAppend ? std::ios::app : std::ios::trunc);
  if (!out_) {
    const int error = errno;
    throw FileSystemError(fmt::format("CsvWriter: cannot open '{}' for writing: {}", path_.string(),
                                      std::strerror(error)),
                          path_, error);
  }
  if (write_header) write_line(header_line);
}

void CsvWriter::write_row(std::span<const CsvValue> row) {
  if (row.size() != header_.size())
    throw InvalidInput(fmt::format("CsvWriter({}): a row of {} fields; expected {} ({})",
                                   path_.string(), row.size(), header_.size(), join(header_)));
  std::vector<std::string> fields;
  fields.reserve(row.size());
  for (const CsvValue& value : row) {
    if (const auto* i = std::get_if<std::int64_t>(&value))
      fields.push_back(fmt::format("{}", *i));
    else if (const auto* x = std::get_if<double>(&value))
      fields.push_back(format_real(*x));
    else
      fields.push_back(std::get<std::string>(value));
  }
  write_line(join(fields));
  ++rows_written_;
}

void CsvWriter::write_row(std::span<const double> row) {
  std::vector<CsvValue> values(row.begin(), row.end());
  write_row(std::span<const CsvValue>(values));
}

void CsvWriter::finish() {
  if (mode_ == Mode::kReplace) detail::write_file_atomically(path_, buffer_);
}

void CsvWriter::write_line(const std::string& line) {
  if (mode_ == Mode::kReplace) {
    buffer_ += line;
    buffer_ += '\n';
    return;
  }
  // Flushing each line hands it to the OS, so a crash or kill of the run loses at most the
  // line being written (an observer's hook).
  out_ << line << '\n';
  out_.flush();
  if (!out_) {
    // A full disk or a read-only remount: the row is lost (a resume drops an incomplete last
    // row), and the run must not go on as if it were recorded.
    const int error = errno;
    throw FileSystemError(fmt::format("CsvWriter: writing '{}' failed: {}", path_.string(),
                                      error != 0 ? std::strerror(error) : "the stream reported an error"),
                          path_, error);
  }
}

}  // namespace frictopt::io
