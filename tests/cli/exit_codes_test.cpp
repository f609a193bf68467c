// SPDX-License-Identifier: MIT
// The one mapping from exceptions to exit codes (apps/frictopt/exit_codes.hpp, README "Command
// line"): every exception type a command can meet gets its documented code, none escapes.
#include "exit_codes.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <new>
#include <stdexcept>
#include <system_error>

#include "frictopt/core/error.hpp"

namespace {

using namespace frictopt::app;

template <class Exception>
int code_for(Exception e) {
  return run_guarded([&]() -> int { throw e; });
}

TEST(ExitCodes, EveryExceptionTypeHasItsDocumentedCode) {
  EXPECT_EQ(run_guarded([] { return kExitOk; }), 0);
  EXPECT_EQ(run_guarded([] { return kExitNumericalFailure; }), 3);
  EXPECT_EQ(code_for(frictopt::InvalidInput("case.toml: x = 1; expected 2")), kExitInvalidInput);
  EXPECT_EQ(code_for(frictopt::NumericalFailure("the initial state did not solve")), kExitNumericalFailure);
  EXPECT_EQ(code_for(std::bad_alloc()), kExitOutOfMemory);
  EXPECT_EQ(code_for(std::filesystem::filesystem_error("create_directories", "out/x",
                                                      std::make_error_code(std::errc::not_a_directory))),
            kExitFileSystem);
  EXPECT_EQ(code_for(std::ios_base::failure("write")), kExitFileSystem);
  EXPECT_EQ(code_for(std::invalid_argument("stod")), kExitInternalError);  // std::stod on bad text: a bug
  EXPECT_EQ(code_for(std::runtime_error("?")), kExitInternalError);
  EXPECT_EQ(code_for(42), kExitInternalError);
  EXPECT_EQ(kExitInvalidInput, 2);
  EXPECT_EQ(kExitNumericalFailure, 3);
  EXPECT_EQ(kExitOutOfMemory, 4);
  EXPECT_EQ(kExitFileSystem, 5);
}

}  // namespace
