// SPDX-License-Identifier: MIT
#include "case_output_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// 255 − len(".") − len("_iter") − 10 digits − len(".vtu") − len(".XXXXXX.tmp").
constexpr std::size_t kMaxOutputNameBytes = 255 - 1 - 5 - 10 - 4 - 11;

OutputSpec read_output(const TableReader& r, std::string default_name) {
  OutputSpec o;
  o.vtk = r.optional_bool("vtk").value_or(true);
  if ((o.every = r.optional_int("every").value_or(1)) < 1) r.fail_value("every", "every >= 1");
  o.name = r.optional_string("name").value_or(std::move(default_name));
  // The name becomes part of file names: a NUL byte would cut them short (the CSV then
  // overwrote the VTU), a '/' would leave the directory, "." and ".." are directories.
  const bool control = std::any_of(o.name.begin(), o.name.end(),
                                   [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; });
  if (o.name.empty() || control || o.name.find_first_of("/\\") != std::string::npos || o.name == "." ||
      o.name == "..")
    r.fail_value("name", "a non-empty file name without '/', '\\' or control characters (NUL, newline, ...)");
  // The longest file made of the name must fit a file name (NAME_MAX = 255 bytes on Linux):
  // the temporary of a series file, "." + name + "_iter" + 10 digits + ".vtu" + ".XXXXXX.tmp".
  if (o.name.size() > kMaxOutputNameBytes)
    r.fail_value("name", fmt::format("at most {} bytes (it has {}), so that its longest output file name "
                                     "(\".NAME_iterK.vtu.XXXXXX.tmp\") fits the file system's 255",
                                     kMaxOutputNameBytes, o.name.size()));
  return o;
}

}  // namespace

OutputSpec read_output_section(const TableReader& top, std::string_view origin_name) {
  const std::string origin(origin_name);
  // Default output name: the file stem, or the case directory's name for the
  // cases*/<name>/case.toml layout (every case file there is called case.toml).
  const std::filesystem::path origin_path(origin);
  std::string default_name = origin_path.stem() == "case" && origin_path.has_parent_path() &&
                                     !origin_path.parent_path().filename().empty()
                                 ? origin_path.parent_path().filename().string()
                                 : origin_path.stem().string();
  if (const toml::table* output = top.optional_table("output"))
    return read_output(TableReader(*output, "output", origin, {"vtk", "every", "name"}),
                           std::move(default_name));
  OutputSpec defaults;
  defaults.name = std::move(default_name);
  return defaults;
}

}  // namespace frictopt::io::detail
