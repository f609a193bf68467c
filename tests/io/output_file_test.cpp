// SPDX-License-Identifier: MIT
// Outputs are regular files only. A symbolic link, a device or a directory at
// an output path is refused and left as it was (never replaced, never written through), and
// the atomic replacement never clobbers a foreign file next to the target.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/temporary_directory.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/json.hpp"

namespace {

namespace fs = std::filesystem;
using frictopt::testing::read_text;

class OutputFile : public frictopt::testing::TemporaryDirectoryTest {};

TEST_F(OutputFile, ASymbolicLinkIsRefusedAndItsTargetUntouched) {
  const fs::path target = dir_ / "precious.json";
  std::ofstream(target) << "keep me";
  const fs::path link = dir_ / "certificate.json";
  fs::create_symlink(target, link);
  frictopt::io::JsonValue json = frictopt::io::JsonValue::object();
  json["a"] = 1;
  try {
    frictopt::io::write_json(link, json);
    FAIL() << "no InvalidInput";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("symbolic link"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_text(target), "keep me");
  EXPECT_THROW(frictopt::io::CsvWriter(link, {"a"}), frictopt::InvalidInput);
  EXPECT_EQ(read_text(target), "keep me");
}

TEST_F(OutputFile, DevicesAndDirectoriesAreRefused) {
  frictopt::io::JsonValue json = frictopt::io::JsonValue::object();
  try {
    frictopt::io::write_json("/dev/null", json);
    FAIL() << "no InvalidInput";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("character device"), std::string::npos) << e.what();
  }
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  fs::create_directory(dir_ / "summary.json");
  EXPECT_THROW(frictopt::io::write_json(dir_ / "summary.json", json), frictopt::InvalidInput);
}

TEST_F(OutputFile, ARegularFileIsReplacedAndAForeignTmpFileIsNotClobbered) {
  const fs::path path = dir_ / "summary.json";
  std::ofstream(path) << "old";
  std::ofstream(dir_ / "summary.json.tmp") << "foreign";  // the name the old writer used
  frictopt::io::JsonValue json = frictopt::io::JsonValue::object();
  json["a"] = 1;
  frictopt::io::write_json(path, json);
  EXPECT_NE(read_text(path).find("\"a\": 1"), std::string::npos);
  EXPECT_EQ(read_text(dir_ / "summary.json.tmp"), "foreign");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 2);  // no temporary left behind
  // The usual permissions (0666 minus the umask), not mkstemp's 0600.
  EXPECT_NE(fs::status(path).permissions() & fs::perms::group_read, fs::perms::none);
}

}  // namespace
