// SPDX-License-Identifier: MIT
// The checkpoint of an optimization run as JSON: the bundle trust method's whole state, the
// contact state the next state solve starts from, the run's counters and the fingerprint of
// the case and mesh it belongs to. With it `frictopt optimize --resume` repeats the
// uninterrupted run bit for bit (docs/case-format.md, "Run directories").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "frictopt/contact/contact_resultants.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/optim/bundle_trust.hpp"

namespace frictopt::io {

/// What identifies the problem a run solves: the normalized case (every setting except the
/// run controls [optimization] and [output], as dotted key -> canonical value) and the mesh.
struct CaseFingerprint {
  int dim = 0;
  std::map<std::string, std::string> settings;  ///< CaseDescription::problem_settings
  std::uint64_t case_hash = 0;                  ///< FNV-1a 64 of the settings
  std::int64_t num_nodes = 0;
  std::uint64_t mesh_hash = 0;                  ///< FNV-1a 64 of the reference node coordinates
  /// The differences from `other` ("material.young: 70000000000 -> 2.1e+11", "the mesh"),
  /// empty when they are the same problem.
  [[nodiscard]] std::vector<std::string> differences_from(const CaseFingerprint& other) const;
};

/// FNV-1a 64 of the settings (one "key=value\n" line each, in key order). For change
/// detection, not for security.
[[nodiscard]] std::uint64_t hash_settings(const std::map<std::string, std::string>& settings);
/// FNV-1a 64 of raw bytes.
[[nodiscard]] std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t seed = 14695981039346656037ull);

struct RunCheckpoint {
  optim::BundleTrust::IterationSummary method;  ///< after the last completed outer iteration
  CaseFingerprint fingerprint;
  /// The contact forces z the body's next state solve starts from (empty: a cold start).
  Eigen::VectorXd warm_start;
  int warm_start_dim = 0;
  /// The contact forces each step of the loading programs starts from (study::ShapeOracle::
  /// history_warm_starts; empty vector: a cold start; no entries: the static problem). Their
  /// dimension is fingerprint.dim.
  std::vector<Eigen::VectorXd> history_warm_starts;
  double initial_cost = kNaN;        ///< Θ(α⁰), for summary.json
  double elapsed_seconds = 0.0;      ///< over all processes of the run so far
  std::int64_t state_solves = 0;     ///< over all processes of the run so far
  /// The history columns of the centre's evaluation (a resumed process has not evaluated the
  /// centre itself, so its rows repeat these until the next serious step).
  struct CenterColumns {
    std::int64_t coulomb_iterations = 0;
    std::int64_t qp_iterations = 0;
    std::int64_t weak_nodes = 0;
    double state_seconds = 0.0;
    double subgradient_seconds = 0.0;
    /// The centre's load (study::Evaluation::resultants): total normal force, |total tangential
    /// force|, contact area and node counts (NaN and 0 in a checkpoint written without them).
    double normal_force = kNaN;
    double tangential_force = kNaN;
    double contact_area = kNaN;
    std::int64_t stick_nodes = 0;
    std::int64_t slip_nodes = 0;
    std::int64_t separated_nodes = 0;
  } center;
  /// The initial design's forces, areas and counts, for summary.json's comparison of the final
  /// design's load with the initial one (study::load_change_warnings); normal_force NaN when the
  /// checkpoint was written without them.
  contact::ContactResultants initial_load = unknown_load();
  /// ContactResultants with a NaN total normal force: "not recorded".
  static contact::ContactResultants unknown_load() {
    contact::ContactResultants r;
    r.normal_force = kNaN;
    return r;
  }
};

/// Every field (doubles round-trip exactly: JSON numbers are written with 17 significant digits).
[[nodiscard]] JsonValue checkpoint_to_json(const RunCheckpoint& checkpoint);
/// Inverse of checkpoint_to_json; throws InvalidInput naming a missing, malformed or
/// out-of-range field (e.g. "checkpoint.json: iteration = -5; expected 0 <= iteration <= 1000000000").
[[nodiscard]] RunCheckpoint checkpoint_from_json(const JsonValue& json, const std::string& origin = "checkpoint");

/// Reads a checkpoint file written by write_json(checkpoint_to_json(...)).
[[nodiscard]] RunCheckpoint read_checkpoint(const std::filesystem::path& path);

}  // namespace frictopt::io
