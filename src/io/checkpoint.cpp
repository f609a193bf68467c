// SPDX-License-Identifier: MIT
#include "frictopt/io/checkpoint.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "frictopt/core/error.hpp"

namespace frictopt::io {
namespace {

Eigen::VectorXd vector_of(const JsonValue& v) {
  const auto& a = v.as_array();
  Eigen::VectorXd out(static_cast<Eigen::Index>(a.size()));
  for (std::size_t i = 0; i < a.size(); ++i) out(static_cast<Eigen::Index>(i)) = a[i].as_number();
  return out;
}

// NaN is stored as null (JSON has no NaN).
double number_of(const JsonValue& v) { return v.is_null() ? kNaN : v.as_number(); }

optim::StepKind parse_step(const std::string& text) {
  for (optim::StepKind k : {optim::StepKind::kStart, optim::StepKind::kSerious, optim::StepKind::kNull,
                            optim::StepKind::kLineSearchSerious, optim::StepKind::kLineSearchNull})
    if (optim::to_string(k) == text) return k;
  throw InvalidInput("checkpoint: step = '" + text + "' is unknown");
}

}  // namespace

JsonValue checkpoint_to_json(const optim::BundleTrust::IterationSummary& s) {
  JsonValue j = JsonValue::object();
  j["format"] = "frictopt-bundle-trust-checkpoint-1";
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
  JsonValue bundle = JsonValue::array();
  for (const optim::BundleElement& e : s.bundle) {
    JsonValue element = JsonValue::object();
    element["g"] = e.g;
    element["lin_err"] = e.lin_err;
    element["distance"] = e.distance;
    element["locality"] = e.locality;
    element["y"] = e.y;
    element["is_center"] = e.is_center;
    bundle.push_back(std::move(element));
  }
  j["bundle"] = std::move(bundle);
  return j;
}

optim::BundleTrust::IterationSummary checkpoint_from_json(const JsonValue& j) {
  try {
    if (!j.contains("format") || j.at("format").as_string() != "frictopt-bundle-trust-checkpoint-1")
      throw InvalidInput("checkpoint: format is not frictopt-bundle-trust-checkpoint-1");
    optim::BundleTrust::IterationSummary s;
    s.iteration = static_cast<int>(j.at("iteration").as_integer());
    s.evaluations = static_cast<int>(j.at("evaluations").as_integer());
    s.serious_steps = static_cast<int>(j.at("serious_steps").as_integer());
    s.null_steps = static_cast<int>(j.at("null_steps").as_integer());
    s.step = parse_step(j.at("step").as_string());
    s.inner_trials = static_cast<int>(j.at("inner_trials").as_integer());
    s.x = vector_of(j.at("x"));
    s.f = number_of(j.at("f"));
    s.t = number_of(j.at("t"));
    s.t_max = number_of(j.at("t_max"));
    s.stationarity = number_of(j.at("stationarity"));
    s.aggregate_error = number_of(j.at("aggregate_error"));
    s.predicted_change = number_of(j.at("predicted_change"));
    s.z_prev = vector_of(j.at("z_prev"));
    s.sigma_prev = number_of(j.at("sigma_prev"));
    s.objective_scale = number_of(j.at("objective_scale"));
    // Absent in checkpoints written before the relative stopping test: resume() rebuilds them.
    for (auto [key, field] : {std::pair{"f_start", &s.f_start}, std::pair{"g_start_norm", &s.g_start_norm}, std::pair{"t_start", &s.t_start},
                              std::pair{"t_reference", &s.t_reference}})
      if (j.contains(key)) *field = number_of(j.at(key));
    for (const JsonValue& e : j.at("bundle").as_array()) {
      optim::BundleElement element;
      element.g = vector_of(e.at("g"));
      element.lin_err = number_of(e.at("lin_err"));
      element.distance = number_of(e.at("distance"));
      element.locality = number_of(e.at("locality"));
      element.y = vector_of(e.at("y"));
      element.is_center = e.at("is_center").as_bool();
      s.bundle.push_back(std::move(element));
    }
    return s;
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("checkpoint is malformed: ") + e.what());
  }
}

optim::BundleTrust::IterationSummary read_checkpoint(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(fmt::format("{}: cannot read the checkpoint (was the run started with this directory?)", path.string()));
  std::stringstream text;
  text << in.rdbuf();
  return checkpoint_from_json(parse_json(text.str()));
}

}  // namespace frictopt::io
