// SPDX-License-Identifier: MIT
#include "atomic_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <system_error>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InvalidInput(
          fmt::format("cannot write '{}' (does its directory exist?)", path.string()));
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) throw InvalidInput(fmt::format("writing '{}' failed", temporary.string()));
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(temporary, ec);
    throw InvalidInput(fmt::format("cannot replace '{}': {}", path.string(), reason));
  }
}

}  // namespace frictopt::io::detail
