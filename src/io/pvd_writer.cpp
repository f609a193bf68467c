// SPDX-License-Identifier: MIT
// Hand-written XML: VTK's C++ libraries have no .pvd writer (ParaView's vtkPVDWriter lives in
// ParaView, not VTK), and the format is a six-line list of <DataSet> elements.
#include "frictopt/io/pvd_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <string>

#include "atomic_file.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io {
namespace {

std::string xml_escaped(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

void write_pvd(const std::filesystem::path& pvd_path, std::span<const PvdEntry> entries) {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const PvdEntry& e = entries[i];
    if (!std::isfinite(e.time))
      throw InvalidInput(
          fmt::format("write_pvd({}): entry {} has time {}; expected a finite "
                      "number",
                      pvd_path.string(), i, e.time));
    if (e.file.empty() || e.file.is_absolute())
      throw InvalidInput(
          fmt::format("write_pvd({}): entry {} has file '{}'; expected a path "
                      "relative to the .pvd's directory",
                      pvd_path.string(), i, e.file.string()));
    // "{}" prints the shortest decimal that reads back as the same double.
    xml += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                       xml_escaped(e.file.generic_string()));
  }
  xml += "  </Collection>\n</VTKFile>\n";
  detail::write_file_atomically(pvd_path, xml);
}

PvdWriter::PvdWriter(std::filesystem::path pvd_path) : pvd_path_(std::move(pvd_path)) {
  write_pvd(pvd_path_, entries_);
}

void PvdWriter::add(double time, const std::filesystem::path& dataset) {
  if (!entries_.empty() && !(time > entries_.back().time))
    throw InvalidInput(
        fmt::format("PvdWriter({}): time {} after time {}; expected increasing "
                    "times",
                    pvd_path_.string(), time, entries_.back().time));
  std::filesystem::path relative = dataset;
  if (dataset.is_absolute()) {
    const std::filesystem::path base =
        std::filesystem::absolute(pvd_path_).parent_path().lexically_normal();
    relative = dataset.lexically_normal().lexically_relative(base);
  }
  entries_.push_back({time, relative});
  try {
    write_pvd(pvd_path_, entries_);
  } catch (...) {
    entries_.pop_back();  // keep entries() equal to what is on disk
    throw;
  }
}

}  // namespace frictopt::io
