// SPDX-License-Identifier: MIT
// `frictopt certify`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

// frictopt certify: the optimality certificate (thesis §5.3; docs/theory/stationarity.md) of a
// run's final design, printed and written to RUN_DIR/certificate.json. Reads RUN_DIR/case.toml (the
// copy `optimize` made) and RUN_DIR/final_design.json.
int run_certify(const std::filesystem::path& run_dir, int cap, double sample_radius, int samples) {
  using namespace frictopt;
  io::RunDirectory run(run_dir, io::RunOpening::kExisting);
  const std::filesystem::path case_path = run.store_case();
  const std::filesystem::path design_path = run.file(io::RunDirectory::kFinalDesign);
  const io::CaseDescription description = io::load_case(case_path);
  const study::BodyDefinition definition = description.body;
  if (!definition.contact) throw InvalidInput(case_path.string() + ": certify needs a [contact] table");
  study::ElasticBody body(definition);
  run.check_run_fingerprint(io::fingerprint_of(description, body));  // case.toml edited after the run: refused
  const Eigen::VectorXd alpha = io::read_design_file(design_path, body.num_design_variables());
  study::ShapeOracle oracle(body, description.required_cost());
  study::CertifyOptions options;
  options.cap = cap;
  options.sample_radius = sample_radius;
  options.samples = samples;
  const study::Certificate c = study::certify(oracle, alpha, options);
  fmt::print("{}: {} design variables, {} contact nodes, cost {}\n{}", run_dir.string(),
             body.num_design_variables(), body.contact_boundary()->num_nodes(), oracle.cost().name(), c.report());
  io::JsonValue json = io::JsonValue::object();
  if (const study::OrientationDesign* o = body.orientation_design()) {  // x = (α, s)
    const double phi_deg = o->angle(alpha(alpha.size() - 1)) * 180.0 / std::numbers::pi;
    fmt::print("friction orientation φ = {:.6f} deg (the last of the {} variables, s = k φ, k = {:.6e} m/rad; the "
               "generators' last row is dΘ/ds)\n",
               phi_deg, alpha.size(), o->scale());
    json["friction_orientation_deg"] = phi_deg;
  }
  // The load the certified design carries against the initial design's (one more state solve,
  // after the certificate): a design can be stationary for a cost it lowered by carrying less.
  io::add_members(json, io::load_comparison(oracle, alpha, body.initial_design()));
  for (const io::JsonValue& w : json.at("warnings").as_array()) fmt::print("warning: {}\n", w.as_string());
  json["command"] = "certify";
  io::add_members(json, io::run_environment());
  json["case"] = case_path.string();
  json["design"] = design_path.string();
  json["cost"] = oracle.cost().name();
  io::add_members(json, io::to_json(c, options));
  run.write_json_file(io::RunDirectory::kCertificate, json);
  fmt::print("wrote {}\n", run.file(io::RunDirectory::kCertificate).string());
  return c.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

}  // namespace frictopt::app
