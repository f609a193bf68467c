// SPDX-License-Identifier: MIT
// Runs the frictopt binary from a test and captures its exit code and output. The binary's path
// comes from the FRICTOPT_BINARY compile definition (see tests/cli/CMakeLists.txt).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <system_error>
#include <vector>

#include "common/temporary_directory.hpp"

namespace frictopt::testing {

/// Writes `text` to `path` byte for byte (a case variant, a damaged run file).
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// `text` with the first line "key = ..." replaced by "key = value" (a case file's setting);
/// fails the test when there is no such line.
inline std::string replace_key(const std::string& text, const std::string& key, const std::string& value) {
  const std::regex line("^" + key + R"( *=[^\n]*)", std::regex::multiline);
  EXPECT_TRUE(std::regex_search(text, line)) << "no '" << key << " =' line";
  return std::regex_replace(text, line, key + " = " + value, std::regex_constants::format_first_only);
}

struct RunResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `frictopt <arguments>`; the log file is unique per test and process, so tests may run
/// in parallel (ctest -j).
inline RunResult run_frictopt(const std::string& arguments) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string tag = info ? std::string(info->test_suite_name()) + "." + info->name() : "frictopt";
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() / ("frictopt_" + tag + "_" + std::to_string(::getpid()) + ".log");
  const std::string command = std::string(FRICTOPT_BINARY) + " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  RunResult result{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(log)};
  std::filesystem::remove(log);
  return result;
}

/// The directories fresh_directory() made in this process: removed at exit when every test of
/// the process passed (a failing test leaves its outputs for inspection).
struct FreshDirectories {
  std::vector<std::filesystem::path> paths;
  ~FreshDirectories() {
    if (!::testing::UnitTest::GetInstance()->Passed()) return;
    std::error_code ignored;
    for (const auto& p : paths) std::filesystem::remove_all(p, ignored);
  }
};

/// An empty directory under the temporary directory, removed first if it exists; the process id
/// in its name keeps two test runs on one machine (a local run and CI) apart.
inline std::filesystem::path fresh_directory(const std::string& name) {
  static FreshDirectories made;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("frictopt_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  made.paths.push_back(dir);
  return dir;
}

}  // namespace frictopt::testing
