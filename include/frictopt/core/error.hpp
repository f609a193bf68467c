// SPDX-License-Identifier: MIT
// The error types and the assert macro every frictopt module may use:
// bad input at an API boundary throws InvalidInput; a result a caller cannot do without
// that a solver failed to produce throws NumericalFailure; broken invariants are FRICTOPT_ASSERT.
#pragma once

#include <source_location>
#include <stdexcept>
#include <string>

namespace frictopt {

/// Bad input at an API boundary (case file, CLI, public function, Options). The message names
/// the field, its value and what was expected, e.g.
/// "case.toml: friction.mu[2] = -0.1; expected >= 0".
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A solver failed where the caller cannot go on without its result (e.g. the state a cost
/// is normalized by). Solvers themselves report non-convergence as a Status in their Summary;
/// this is for the layers above that need the result. The command line maps it to exit code 3,
/// the same as a failed solve reported by status.
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
/// Prints "assert failed: <condition> (<message>) at <file>:<line>" to stderr and aborts.
[[noreturn]] void assert_failed(const char* condition, const std::string& message,
                                const std::source_location& where);
}  // namespace detail

}  // namespace frictopt

// Active in Debug builds (NDEBUG undefined) and in sanitizer builds (FRICTOPT_ENABLE_ASSERTS).
#if !defined(NDEBUG) || defined(FRICTOPT_ENABLE_ASSERTS)
#define FRICTOPT_ASSERT(cond, msg)                                                   \
  do {                                                                               \
    if (!(cond))                                                                     \
      ::frictopt::detail::assert_failed(#cond, (msg), std::source_location::current()); \
  } while (0)
#else
#define FRICTOPT_ASSERT(cond, msg) \
  do {                             \
  } while (0)
#endif
