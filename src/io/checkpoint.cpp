// SPDX-License-Identifier: MIT
#include "frictopt/io/checkpoint.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"
#include "input_file.hpp"

namespace frictopt::io {
namespace {

// Format 3 adds the checksum and the method's safeguards (IterationSummary::restarts, ...);
// format 2 (no checksum) is still read.
constexpr std::string_view kFormat = "frictopt-run-checkpoint-3";
constexpr std::string_view kFormat2 = "frictopt-run-checkpoint-2";
// Counters of a run (iterations, evaluations, solves): a billion is far beyond any run and
// keeps every counter inside int.
constexpr std::int64_t kMaxCount = 1'000'000'000;

// Reads the checkpoint's fields with the origin and the field's name in every message.
class Fields {
 public:
  Fields(const JsonValue& object, std::string origin, std::string prefix = "")
      : object_(object), origin_(std::move(origin)), prefix_(std::move(prefix)) {}

  const JsonValue& at(std::string_view key) const {
    if (!object_.is_object() || !object_.contains(key))
      throw InvalidInput(fmt::format("{}: {} is missing", origin_, name(key)));
    return object_.at(key);
  }
  std::string name(std::string_view key) const { return prefix_ + std::string(key); }

  std::int64_t count(std::string_view key, std::int64_t lo = 0, std::int64_t hi = kMaxCount) const {
    const JsonValue& v = at(key);
    if (!v.is_integer())
      fail_field(origin_, name(key), describe(v), fmt::format("an integer in [{}, {}]", lo, hi));
    const std::int64_t i = v.as_integer();
    if (i < lo || i > hi) fail_field(origin_, name(key), std::to_string(i), fmt::format("{} <= {} <= {}", lo, key, hi));
    return i;
  }
  // NaN is stored as null (JSON has no NaN); `finite` refuses it.
  double number(std::string_view key, bool finite = false) const {
    const JsonValue& v = at(key);
    if (v.is_null() && !finite) return kNaN;
    if (!v.is_integer() && !v.is_real()) fail_field(origin_, name(key), describe(v), "a number");
    const double x = v.as_number();
    if (finite && !std::isfinite(x)) fail_field(origin_, name(key), format_number(x), "a finite number");
    return x;
  }
  double positive(std::string_view key) const {
    const double x = number(key, true);
    require_field(x > 0, origin_, name(key), x, "a finite number > 0");
    return x;
  }
  Eigen::VectorXd vector(std::string_view key, Eigen::Index size = -1) const {
    const JsonValue& v = at(key);
    if (!v.is_array()) fail_field(origin_, name(key), describe(v), "a list of numbers");
    const auto& a = v.as_array();
    if (size >= 0 && static_cast<Eigen::Index>(a.size()) != size)
      fail_field(origin_, name(key), fmt::format("a list of {} numbers", a.size()), fmt::format("{} numbers", size));
    Eigen::VectorXd out(static_cast<Eigen::Index>(a.size()));
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_integer() && !a[i].is_real())
        fail_field(origin_, fmt::format("{}[{}]", name(key), i), describe(a[i]), "a finite number");
      out(static_cast<Eigen::Index>(i)) = a[i].as_number();
      if (!std::isfinite(out(static_cast<Eigen::Index>(i))))
        fail_field(origin_, fmt::format("{}[{}]", name(key), i), "non-finite", "a finite number");
    }
    return out;
  }
  std::string text(std::string_view key) const {
    const JsonValue& v = at(key);
    if (!v.is_string()) fail_field(origin_, name(key), describe(v), "a string");
    return v.as_string();
  }
  std::uint64_t hash(std::string_view key) const {
    const std::string h = text(key);
    std::uint64_t value = 0;
    if (h.size() != 16 || h.find_first_not_of("0123456789abcdef") != std::string::npos)
      fail_field(origin_, name(key), "\"" + h + "\"", "16 lowercase hexadecimal digits");
    std::istringstream(h) >> std::hex >> value;
    return value;
  }

 private:
  static std::string describe(const JsonValue& v) {
    if (v.is_null()) return "null";
    return to_json_string(v, -1).substr(0, 40);
  }
  const JsonValue& object_;
  std::string origin_;
  std::string prefix_;
};

optim::StepKind parse_step(const std::string& text, const std::string& origin) {
  for (optim::StepKind k : {optim::StepKind::kStart, optim::StepKind::kSerious, optim::StepKind::kNull,
                            optim::StepKind::kLineSearchSerious, optim::StepKind::kLineSearchNull})
    if (optim::to_string(k) == text) return k;
  fail_field(origin, "step", "'" + text + "'", "start, serious, null or a line-search step");
}

std::string hex(std::uint64_t h) { return fmt::format("{:016x}", h); }

// FNV-1a 64 of the compact JSON text of every member of `j` but "checksum": the same text for
// the object written and the object read back (doubles are printed in their shortest
// round-trip form, members in their order). It detects an edited or damaged checkpoint whose
// edit still parses (a falsified centre value); it is no protection against a deliberate
// forgery, which would recompute it.
std::string checksum_of(const JsonValue& j) {
  JsonValue body = JsonValue::object();
  for (const auto& [key, value] : j.as_object())
    if (key != "checksum") body[key] = value;
  const std::string text = to_json_string(body, -1);
  return hex(fnv1a64(text.data(), text.size()));
}

}  // namespace

std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t seed) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::uint64_t h = seed;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::uint64_t hash_settings(const std::map<std::string, std::string>& settings) {
  std::uint64_t h = fnv1a64(nullptr, 0);
  for (const auto& [key, value] : settings) {
    const std::string line = key + "=" + value + "\n";
    h = fnv1a64(line.data(), line.size(), h);
  }
  return h;
}

std::vector<std::string> CaseFingerprint::differences_from(const CaseFingerprint& other) const {
  std::vector<std::string> out;
  if (dim != other.dim) out.push_back(fmt::format("geometry.dim: {} -> {}", other.dim, dim));
  auto a = other.settings.begin();
  auto b = settings.begin();
  while (a != other.settings.end() || b != settings.end()) {
    if (b == settings.end() || (a != other.settings.end() && a->first < b->first)) {
      out.push_back(fmt::format("{}: {} -> (absent)", a->first, a->second));
      ++a;
    } else if (a == other.settings.end() || b->first < a->first) {
      out.push_back(fmt::format("{}: (absent) -> {}", b->first, b->second));
      ++b;
    } else {
      if (a->second != b->second) out.push_back(fmt::format("{}: {} -> {}", a->first, a->second, b->second));
      ++a;
      ++b;
    }
  }
  if (out.empty() && case_hash != other.case_hash) out.push_back("the normalized case (hash)");
  if (num_nodes != other.num_nodes || mesh_hash != other.mesh_hash)
    out.push_back(fmt::format("the mesh ({} nodes, hash {} -> {} nodes, hash {})", other.num_nodes,
                              hex(other.mesh_hash), num_nodes, hex(mesh_hash)));
  return out;
}

JsonValue checkpoint_to_json(const RunCheckpoint& c) {
  const optim::BundleTrust::IterationSummary& s = c.method;
  JsonValue j = JsonValue::object();
  j["format"] = std::string(kFormat);
  j["iteration"] = s.iteration;
  j["evaluations"] = s.evaluations;
  j["serious_steps"] = s.serious_steps;
  j["null_steps"] = s.null_steps;
  j["step"] = std::string(optim::to_string(s.step));
  j["inner_trials"] = s.inner_trials;
  j["x"] = s.x;
  j["f"] = s.f;
  j["t"] = s.t;
  j["t_max"] = s.t_max;
  j["stationarity"] = s.stationarity;
  j["aggregate_error"] = s.aggregate_error;
  j["predicted_change"] = s.predicted_change;
  j["z_prev"] = s.z_prev;
  j["sigma_prev"] = s.sigma_prev;
  j["objective_scale"] = s.objective_scale;
  j["f_start"] = s.f_start;  // start data of the relative stopping test
  j["g_start_norm"] = s.g_start_norm;
  j["t_start"] = s.t_start;
  j["t_reference"] = s.t_reference;
  // x_1: the locality unit grows with ‖x_k − x_1‖∞ (docs/optim.md); empty before a run
  if (s.x_start.size() > 0) j["x_start"] = s.x_start;
  // The opt-in variable metric (docs/optim.md, "Variable metric"): g(x_1) for its G, the metric
  // and its secant pairs (column-major, `pairs` columns of n), so that a resume continues it.
  if (s.g_start.size() > 0) j["g_start"] = s.g_start;
  j["null_streak"] = s.null_streak;
  // The method's safeguards (IterationSummary), so that the resumed run continues them.
  j["restarts"] = s.restarts;
  j["tightenings"] = s.tightenings;
  j["test_factor"] = s.test_factor;
  j["resolution_reached"] = s.resolution_reached;
  j["bundle_size_used"] = s.bundle_size_used;
  // The restart check (docs/optim.md, "Restart check"): how many were started and the one in
  // progress, so that a resume continues the check instead of starting it again.
  j["restart_checks"] = s.restart_checks;
  if (!std::isnan(s.check_value)) {
    j["check_value"] = s.check_value;
    j["check_tolerance"] = s.check_tolerance;
    j["check_iteration"] = s.check_iteration;
  }
  const optim::DiagonalMetric& m = s.metric;
  if (!m.is_identity() || m.steps.size() > 0 || m.resets > 0) {
    JsonValue metric = JsonValue::object();
    metric["h"] = m.h;
    metric["pairs"] = static_cast<std::int64_t>(m.steps.cols());
    metric["steps"] = Eigen::VectorXd(m.steps.reshaped());
    metric["differences"] = Eigen::VectorXd(m.differences.reshaped());
    metric["updates"] = m.updates;
    metric["resets"] = m.resets;
    j["metric"] = std::move(metric);
  }
  JsonValue bundle = JsonValue::array();
  for (const optim::BundleElement& e : s.bundle) {
    JsonValue element = JsonValue::object();
    element["g"] = e.g;
    element["lin_err"] = e.lin_err;
    element["distance"] = e.distance;
    element["locality"] = e.locality;
    element["y"] = e.y;
    element["is_center"] = e.is_center;
    element["piece_gap"] = e.piece_gap;
    bundle.push_back(std::move(element));
  }
  j["bundle"] = std::move(bundle);
  JsonValue run = JsonValue::object();
  run["initial_cost"] = c.initial_cost;
  run["elapsed_seconds"] = c.elapsed_seconds;
  run["state_solves"] = c.state_solves;
  run["warm_start_dim"] = c.warm_start_dim;
  run["warm_start"] = c.warm_start;
  if (!c.history_warm_starts.empty()) {
    JsonValue states = JsonValue::array();
    for (const Eigen::VectorXd& z : c.history_warm_starts) states.push_back(JsonValue(z));
    run["history_warm_starts"] = std::move(states);
  }
  JsonValue center = JsonValue::object();
  center["coulomb_iterations"] = c.center.coulomb_iterations;
  center["qp_iterations"] = c.center.qp_iterations;
  center["weak_nodes"] = c.center.weak_nodes;
  center["state_seconds"] = c.center.state_seconds;
  center["subgradient_seconds"] = c.center.subgradient_seconds;
  center["normal_force"] = c.center.normal_force;
  center["tangential_force"] = c.center.tangential_force;
  center["contact_area"] = c.center.contact_area;
  center["stick_nodes"] = c.center.stick_nodes;
  center["slip_nodes"] = c.center.slip_nodes;
  center["separated_nodes"] = c.center.separated_nodes;
  run["center"] = std::move(center);
  if (std::isfinite(c.initial_load.normal_force)) {
    const contact::ContactResultants& r = c.initial_load;
    JsonValue load = JsonValue::object();
    load["dim"] = r.dim;
    load["normal_force"] = r.normal_force;
    load["tangential_force"] = Eigen::VectorXd(r.tangential_force);
    load["tangential_force_norm"] = r.tangential_force_norm;
    load["contact_area"] = r.contact_area;
    load["num_stick"] = r.num_stick;
    load["num_slip"] = r.num_slip;
    load["num_separated"] = r.num_separated;
    run["initial_load"] = std::move(load);
  }
  j["run"] = std::move(run);
  JsonValue fingerprint = JsonValue::object();
  fingerprint["dim"] = c.fingerprint.dim;
  fingerprint["case_hash"] = hex(c.fingerprint.case_hash);
  fingerprint["num_nodes"] = c.fingerprint.num_nodes;
  fingerprint["mesh_hash"] = hex(c.fingerprint.mesh_hash);
  JsonValue settings = JsonValue::object();
  for (const auto& [key, value] : c.fingerprint.settings) settings[key] = value;
  fingerprint["settings"] = std::move(settings);
  j["fingerprint"] = std::move(fingerprint);
  j["checksum"] = checksum_of(j);
  return j;
}

RunCheckpoint checkpoint_from_json(const JsonValue& j, const std::string& origin) {
  const Fields top(j, origin);
  const bool format2 = j.is_object() && j.contains("format") && j.at("format").is_string() &&
                       j.at("format").as_string() == kFormat2;
  if (!format2 &&
      (!j.is_object() || !j.contains("format") || !j.at("format").is_string() || j.at("format").as_string() != kFormat))
    throw InvalidInput(fmt::format("{}: format is not {} (a checkpoint of an older frictopt or another file); "
                                   "start the run again with --force",
                                   origin, kFormat));

  RunCheckpoint c;
  optim::BundleTrust::IterationSummary& s = c.method;
  s.iteration = static_cast<int>(top.count("iteration"));
  s.evaluations = static_cast<int>(top.count("evaluations", 1));
  s.serious_steps = static_cast<int>(top.count("serious_steps"));
  s.null_steps = static_cast<int>(top.count("null_steps"));
  if (s.serious_steps + s.null_steps != s.iteration)
    throw InvalidInput(fmt::format("{}: serious_steps + null_steps = {} + {}; expected = iteration = {}", origin,
                                   s.serious_steps, s.null_steps, s.iteration));
  s.step = parse_step(top.text("step"), origin);
  s.inner_trials = static_cast<int>(top.count("inner_trials"));
  s.x = top.vector("x");
  const Eigen::Index n = s.x.size();
  if (n == 0) fail_field(origin, "x", "[]", "the design (a non-empty list)");
  s.f = top.number("f", true);
  s.t = top.positive("t");
  s.t_max = top.positive("t_max");
  s.stationarity = top.number("stationarity");
  s.aggregate_error = top.number("aggregate_error");
  s.predicted_change = top.number("predicted_change");
  s.z_prev = top.vector("z_prev", n);
  s.sigma_prev = top.number("sigma_prev");
  s.objective_scale = top.positive("objective_scale");
  // Start data of the relative stopping test (docs/optim.md); absent in checkpoints written
  // before it (NaN: resume() rebuilds them).
  for (auto [key, field] : {std::pair{"f_start", &s.f_start}, std::pair{"g_start_norm", &s.g_start_norm},
                            std::pair{"t_start", &s.t_start}, std::pair{"t_reference", &s.t_reference}})
    if (j.contains(key)) *field = top.number(key);
  if (j.contains("x_start")) s.x_start = top.vector("x_start", n);  // absent: resume() uses x
  // Variable metric state (absent: identity, as before the option existed).
  if (j.contains("g_start")) s.g_start = top.vector("g_start", n);
  if (j.contains("null_streak")) s.null_streak = static_cast<int>(top.count("null_streak"));
  // The method's safeguards (absent in format 2: a fresh run's values).
  if (j.contains("restarts")) s.restarts = static_cast<int>(top.count("restarts"));
  if (j.contains("tightenings")) s.tightenings = static_cast<int>(top.count("tightenings"));
  if (j.contains("test_factor")) {
    s.test_factor = top.positive("test_factor");
    if (s.test_factor > 1.0) fail_field(origin, "test_factor", format_number(s.test_factor), "0 < test_factor <= 1");
  }
  if (j.contains("resolution_reached")) {
    const JsonValue& v = top.at("resolution_reached");
    if (!v.is_bool()) fail_field(origin, "resolution_reached", "not a boolean", "true or false");
    s.resolution_reached = v.as_bool();
  }
  if (j.contains("bundle_size_used")) s.bundle_size_used = static_cast<int>(top.count("bundle_size_used", 0, 1'000'000));
  // The restart check (absent in checkpoints written before it: none started, none in progress).
  if (j.contains("restart_checks")) s.restart_checks = static_cast<int>(top.count("restart_checks"));
  if (j.contains("check_value")) {
    s.check_value = top.number("check_value", true);
    s.check_tolerance = top.number("check_tolerance", true);
    if (!(s.check_tolerance >= 0))
      fail_field(origin, "check_tolerance", format_number(s.check_tolerance), "a tolerance >= 0");
    s.check_iteration = static_cast<int>(top.count("check_iteration", 0, s.iteration));
  }
  if (j.contains("metric")) {
    const Fields m(top.at("metric"), origin, "metric.");
    optim::DiagonalMetric& metric = s.metric;
    metric.h = m.vector("h");
    if (metric.h.size() != 0 && metric.h.size() != n)
      fail_field(origin, "metric.h", fmt::format("a list of {} numbers", metric.h.size()),
                 fmt::format("[] (identity) or {} numbers", n));
    for (Eigen::Index i = 0; i < metric.h.size(); ++i)
      if (!(metric.h(i) > 0.0)) fail_field(origin, fmt::format("metric.h[{}]", i), format_number(metric.h(i)), "> 0");
    const Eigen::Index pairs = static_cast<Eigen::Index>(m.count("pairs"));
    metric.steps = m.vector("steps", n * pairs).reshaped(n, pairs);
    metric.differences = m.vector("differences", n * pairs).reshaped(n, pairs);
    metric.updates = static_cast<int>(m.count("updates"));
    metric.resets = static_cast<int>(m.count("resets"));
  }
  const JsonValue& bundle = top.at("bundle");
  if (!bundle.is_array() || bundle.as_array().empty()) fail_field(origin, "bundle", "empty", "a non-empty list");
  for (std::size_t i = 0; i < bundle.as_array().size(); ++i) {
    const Fields e(bundle.as_array()[i], origin, fmt::format("bundle[{}].", i));
    optim::BundleElement element;
    element.g = e.vector("g", n);
    element.lin_err = e.number("lin_err", true);
    element.distance = e.number("distance", true);
    element.locality = e.number("locality", true);
    // y: the trial point (n numbers), or [] for the aggregate element (BundleElement::is_aggregate).
    element.y = e.vector("y");
    if (element.y.size() != 0 && element.y.size() != n)
      fail_field(origin, e.name("y"), fmt::format("a list of {} numbers", element.y.size()),
                 fmt::format("{} numbers (a trial point) or [] (the aggregate)", n));
    const JsonValue& center = e.at("is_center");
    if (!center.is_bool()) fail_field(origin, e.name("is_center"), "not a boolean", "true or false");
    element.is_center = center.as_bool();
    // The centre's element is the cut taken at x itself (lin_err 0); anything else is a
    // checkpoint that disagrees with itself.
    if (element.is_center && (element.y.size() != n || element.y != s.x || element.lin_err != 0.0))
      throw InvalidInput(fmt::format("{}: bundle[{}] is the centre's element but its y or lin_err disagrees with x "
                                     "(expected y = x, lin_err = 0); the checkpoint was edited or damaged",
                                     origin, i));
    // Absent in checkpoints written before piece gaps were kept: those bundles held cuts of f.
    if (bundle.as_array()[i].contains("piece_gap")) element.piece_gap = e.number("piece_gap", true);
    s.bundle.push_back(std::move(element));
  }
  const Fields run(top.at("run"), origin, "run.");
  c.initial_cost = run.number("initial_cost", true);
  c.elapsed_seconds = run.number("elapsed_seconds", true);
  c.state_solves = run.count("state_solves");
  c.warm_start_dim = static_cast<int>(run.count("warm_start_dim", 0, 3));
  c.warm_start = run.vector("warm_start");
  if (c.warm_start.size() > 0 && (c.warm_start_dim < 2 || c.warm_start.size() % c.warm_start_dim != 0))
    fail_field(origin, "run.warm_start", fmt::format("a list of {} numbers", c.warm_start.size()),
               fmt::format("a multiple of run.warm_start_dim = {} (2 or 3)", c.warm_start_dim));
  const Fields center(run.at("center"), origin, "run.center.");
  if (top.at("run").contains("history_warm_starts")) {
    const JsonValue& states = run.at("history_warm_starts");
    if (!states.is_array()) fail_field(origin, "run.history_warm_starts", "not a list", "a list of lists of numbers");
    for (std::size_t k = 0; k < states.as_array().size(); ++k) {
      JsonValue holder = JsonValue::object();
      holder["z"] = states.as_array()[k];
      const Fields state(holder, origin, fmt::format("run.history_warm_starts[{}].", k));
      c.history_warm_starts.push_back(state.vector("z"));
    }
  }
  c.center.coulomb_iterations = center.count("coulomb_iterations");
  c.center.qp_iterations = center.count("qp_iterations", 0, std::numeric_limits<std::int64_t>::max());
  c.center.weak_nodes = center.count("weak_nodes", 0, std::numeric_limits<std::int64_t>::max());
  c.center.state_seconds = center.number("state_seconds", true);
  c.center.subgradient_seconds = center.number("subgradient_seconds", true);
  // The load columns and the initial load came with the forces in history.csv: a checkpoint
  // written before them resumes with the columns empty (NaN) and no load comparison.
  if (top.at("run").at("center").contains("normal_force")) {
    c.center.normal_force = center.number("normal_force");
    c.center.tangential_force = center.number("tangential_force");
    c.center.contact_area = center.number("contact_area");
    c.center.stick_nodes = center.count("stick_nodes");
    c.center.slip_nodes = center.count("slip_nodes");
    c.center.separated_nodes = center.count("separated_nodes");
  }
  if (top.at("run").contains("initial_load")) {
    const Fields load(run.at("initial_load"), origin, "run.initial_load.");
    contact::ContactResultants& r = c.initial_load;
    r.dim = static_cast<int>(load.count("dim", 2, 3));
    r.normal_force = load.number("normal_force", true);
    r.tangential_force = load.vector("tangential_force", 2);
    r.tangential_force_norm = load.number("tangential_force_norm", true);
    r.contact_area = load.number("contact_area", true);
    r.num_stick = static_cast<int>(load.count("num_stick"));
    r.num_slip = static_cast<int>(load.count("num_slip"));
    r.num_separated = static_cast<int>(load.count("num_separated"));
  }
  const Fields f(top.at("fingerprint"), origin, "fingerprint.");
  c.fingerprint.dim = static_cast<int>(f.count("dim", 2, 3));
  for (std::size_t k = 0; k < c.history_warm_starts.size(); ++k)
    if (c.history_warm_starts[k].size() % c.fingerprint.dim != 0)
      fail_field(origin, fmt::format("run.history_warm_starts[{}]", k),
                 fmt::format("a list of {} numbers", c.history_warm_starts[k].size()),
                 fmt::format("a multiple of fingerprint.dim = {}", c.fingerprint.dim));
  c.fingerprint.case_hash = f.hash("case_hash");
  c.fingerprint.num_nodes = f.count("num_nodes", 1, std::numeric_limits<std::int64_t>::max());
  c.fingerprint.mesh_hash = f.hash("mesh_hash");
  const JsonValue& settings = f.at("settings");
  if (!settings.is_object()) fail_field(origin, "fingerprint.settings", "not an object", "an object of strings");
  for (const auto& [key, value] : settings.as_object()) {
    if (!value.is_string()) fail_field(origin, "fingerprint.settings." + key, "not a string", "a string");
    c.fingerprint.settings[key] = value.as_string();
  }
  if (hash_settings(c.fingerprint.settings) != c.fingerprint.case_hash)
    throw InvalidInput(fmt::format("{}: fingerprint.case_hash does not match fingerprint.settings; the checkpoint "
                                   "was edited or damaged",
                                   origin));
  // Last, so that a field out of range is reported by name first: any other edit.
  if (!format2) {
    const std::string stored = top.text("checksum");
    if (stored != checksum_of(j))
      throw InvalidInput(fmt::format("{}: checksum {} does not match the content ({}): the checkpoint was edited or "
                                     "damaged after frictopt wrote it; a run resumes only from its own checkpoint "
                                     "(start it again with --force)",
                                     origin, detail::printable_excerpt(stored, 20), checksum_of(j)));
  }
  return c;
}

RunCheckpoint read_checkpoint(const std::filesystem::path& path) {
  // A regular file only (a FIFO in its place would block the resume forever), bounded in size.
  return checkpoint_from_json(read_json_file(path, "the checkpoint"), path.string());
}

}  // namespace frictopt::io
