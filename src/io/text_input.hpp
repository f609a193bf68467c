// SPDX-License-Identifier: MIT
// How frictopt's text readers (case files, measurement CSVs) treat a leading UTF-8 byte order
// mark: editors on Windows write one; it is skipped, the same way in every reader.
#pragma once

#include <string_view>

namespace frictopt::io::detail {

inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

/// `text` without a leading UTF-8 byte order mark.
[[nodiscard]] inline std::string_view without_bom(std::string_view text) {
  return text.starts_with(kUtf8Bom) ? text.substr(kUtf8Bom.size()) : text;
}

}  // namespace frictopt::io::detail
