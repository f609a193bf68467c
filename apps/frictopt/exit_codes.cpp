// SPDX-License-Identifier: MIT
#include "exit_codes.hpp"

#include <filesystem>
#include <iostream>
#include <new>

#include "frictopt/core/error.hpp"

namespace frictopt::app {

int run_guarded(const std::function<int()>& command) {
  try {
    return command();
  } catch (const InvalidInput& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitInvalidInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory: the problem does not fit in this machine's memory (see the size "
                 "limits in docs/case-format.md)\n";
    return kExitOutOfMemory;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "error: file system: " << e.what() << '\n';
    return kExitFileSystem;
  } catch (const std::ios_base::failure& e) {
    std::cerr << "error: input/output: " << e.what() << '\n';
    return kExitFileSystem;
  } catch (const std::exception& e) {
    std::cerr << "error: internal error (please report it with the command line and the case): " << e.what()
              << '\n';
    return kExitInternalError;
  } catch (...) {
    std::cerr << "error: internal error: an unknown exception (please report it)\n";
    return kExitInternalError;
  }
}

}  // namespace frictopt::app
