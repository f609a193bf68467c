// SPDX-License-Identifier: MIT
// CSV history files: every row is on disk as soon as write_row returns (an interrupted run
// keeps its history), values read back exactly, and misuse is reported.
#include "frictopt/io/csv_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"

namespace frictopt::io {
namespace {

namespace fs = std::filesystem;

using frictopt::testing::read_text;

class CsvFiles : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(CsvFiles, EachRowIsOnDiskBeforeTheWriterCloses) {
  const fs::path file = dir_ / "history.csv";
  CsvWriter csv(file, {"iteration", "theta", "status"});
  EXPECT_EQ(read_text(file), "iteration,theta,status\n") << "the header is flushed at once";
  csv.write_row({std::int64_t{0}, 1.25, std::string("converged")});
  EXPECT_EQ(read_text(file), "iteration,theta,status\n0,1.25,converged\n");
  csv.write_row({1, 0.1, "max_iterations"});
  EXPECT_EQ(read_text(file), "iteration,theta,status\n0,1.25,converged\n1,0.1,max_iterations\n");
  EXPECT_EQ(csv.rows_written(), 2);
}

TEST_F(CsvFiles, RealsReadBackExactlyAndSpecialValuesAreSpelledForNumpy) {
  const fs::path file = dir_ / "reals.csv";
  const double third = 1.0 / 3.0;
  {
    CsvWriter csv(file, {"a", "b", "c", "d"});
    const double row[] = {third, std::numeric_limits<double>::quiet_NaN(),
                          -std::numeric_limits<double>::infinity(), 1e-300};
    csv.write_row(std::span<const double>(row));
  }
  std::istringstream lines(read_text(file));
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_EQ(row.substr(row.find(',')), ",nan,-inf,1e-300");
  EXPECT_EQ(std::stod(row.substr(0, row.find(','))), third) << "shortest round-trip form";
}

TEST_F(CsvFiles, TextWithSeparatorsIsQuoted) {
  const fs::path file = dir_ / "text.csv";
  CsvWriter csv(file, {"message"});
  csv.write_row({"stalled, step \"0.5\""});
  EXPECT_EQ(read_text(file), "message\n\"stalled, step \"\"0.5\"\"\"\n");
}

TEST_F(CsvFiles, AppendingContinuesAFileWithTheSameHeader) {
  const fs::path file = dir_ / "history.csv";
  {
    CsvWriter csv(file, {"k", "f"});
    csv.write_row({0, 1.0});
  }
  {
    CsvWriter csv(file, {"k", "f"}, CsvWriter::Mode::kAppend);
    csv.write_row({1, 0.5});
  }
  EXPECT_EQ(read_text(file), "k,f\n0,1\n1,0.5\n");
  EXPECT_THROW(CsvWriter(file, {"k", "g"}, CsvWriter::Mode::kAppend), InvalidInput);
  CsvWriter fresh(dir_ / "new.csv", {"k"}, CsvWriter::Mode::kAppend);
  EXPECT_EQ(read_text(dir_ / "new.csv"), "k\n") << "appending to a new file writes the header";
}

TEST_F(CsvFiles, MisuseIsInvalidInput) {
  CsvWriter csv(dir_ / "x.csv", {"a", "b"});
  EXPECT_THROW(csv.write_row({1.0}), InvalidInput);
  EXPECT_THROW(CsvWriter(dir_ / "y.csv", {}), InvalidInput);
  EXPECT_THROW(CsvWriter(dir_ / "y.csv", {"a", "a"}), InvalidInput);
  // A missing directory is the file system's refusal (exit 5), not bad input.
  EXPECT_THROW(CsvWriter(dir_ / "no" / "y.csv", {"a"}), frictopt::io::FileSystemError);
}

}  // namespace
}  // namespace frictopt::io
