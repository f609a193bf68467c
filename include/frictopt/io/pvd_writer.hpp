// SPDX-License-Identifier: MIT
// A ParaView collection (.pvd): the list "time (or iteration) -> .vtu file" that lets
// ParaView play an optimization or load series as an animation.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

namespace frictopt::io {

/// One dataset of a collection.
struct PvdEntry {
  double time = 0.0;           ///< the time step or iteration number shown by ParaView
  std::filesystem::path file;  ///< the dataset, relative to the .pvd's directory
};

/// Writes the collection `entries` to `pvd_path`, replacing it atomically (a temporary file
/// renamed over the old one), so a reader never sees a half-written collection.
/// Throws InvalidInput if a time is not finite, a file name is empty or absolute, or the file
/// cannot be written.
void write_pvd(const std::filesystem::path& pvd_path, std::span<const PvdEntry> entries);

/// Grows a collection one dataset at a time and rewrites the .pvd after each addition, so the
/// collection on disk is complete and well-formed even if the run is interrupted.
class PvdWriter {
 public:
  /// Writes an empty collection to `pvd_path` at once (so a bad path fails early).
  explicit PvdWriter(std::filesystem::path pvd_path);

  /// Adds `dataset` at `time` and rewrites the .pvd. `dataset` may be relative to the .pvd's
  /// directory or absolute, in which case it is stored relative to that directory (so the
  /// output directory can be moved). Throws InvalidInput if `time` is not greater than the
  /// previous time (ParaView orders by time, and equal times would hide a dataset).
  void add(double time, const std::filesystem::path& dataset);

  [[nodiscard]] const std::vector<PvdEntry>& entries() const { return entries_; }
  [[nodiscard]] const std::filesystem::path& path() const { return pvd_path_; }

 private:
  std::filesystem::path pvd_path_;
  std::vector<PvdEntry> entries_;
};

}  // namespace frictopt::io
