// SPDX-License-Identifier: MIT
// `frictopt certify`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/study/identification.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

// frictopt certify: the optimality certificate (thesis §5.3; spec 06 §6) of a run's final design,
// printed and written to RUN_DIR/certificate.json. Reads RUN_DIR/case.toml (the copy `optimize`
// made) and RUN_DIR/final_design.json.
int run_certify(const std::filesystem::path& run_dir, int cap) {
  using namespace frictopt;
  namespace fs = std::filesystem;
  const fs::path case_path = run_dir / "case.toml", design_path = run_dir / "final_design.json";
  if (!fs::is_directory(run_dir)) throw InvalidInput(run_dir.string() + ": the run directory does not exist");
  for (const fs::path& file : {case_path, design_path})
    if (!fs::exists(file))
      throw InvalidInput(fmt::format("{}: missing; expected a run directory written by `frictopt optimize`",
                                     file.string()));
  const io::CaseDescription description = io::load_case(case_path);
  const study::BodyDefinition definition = description.body;
  if (!definition.contact) throw InvalidInput(case_path.string() + ": certify needs a [contact] table");
  study::ElasticBody body(definition);
  const Eigen::VectorXd alpha = io::read_design_file(design_path, definition.shape.num_controls());
  study::ShapeOracle oracle(body, description.required_cost());
  study::CertifyOptions options;
  options.cap = cap;
  const study::Certificate c = study::certify(oracle, alpha, options);
  fmt::print("{}: {} design variables, {} contact nodes, cost {}\n{}", run_dir.string(),
             definition.shape.num_controls(), body.contact_boundary()->num_nodes(), oracle.cost().name(), c.report());

  io::JsonValue json = io::JsonValue::object();
  json["command"] = "certify";
  json["case"] = case_path.string();
  json["design"] = design_path.string();
  json["cost"] = oracle.cost().name();
  json["status"] = std::string(to_string(c.status));
  json["message"] = c.message;
  json["alpha"] = alpha;
  json["value"] = c.value;
  io::JsonValue sets = io::JsonValue::object();
  sets["summary"] = c.index_sets.summary();
  sets["weak_nodes"] = c.index_sets.num_weak_nodes();
  for (auto n : {sensitivity::NormalSet::kStrongContact, sensitivity::NormalSet::kNoContact,
                 sensitivity::NormalSet::kWeakContact})
    sets[sensitivity::to_string(n)] = c.index_sets.count(n);
  io::JsonValue tangential = io::JsonValue::object();
  for (int t = 0; t <= static_cast<int>(sensitivity::TangentialSet::kZeroForce); ++t) {
    const auto set = static_cast<sensitivity::TangentialSet>(t);
    if (c.index_sets.count(set)) tangential[sensitivity::to_string(set)] = c.index_sets.count(set);
  }
  sets["tangential"] = tangential;
  sets["force_tolerance"] = c.index_sets.force_tolerance;
  sets["displacement_tolerance"] = c.index_sets.displacement_tolerance;
  json["index_sets"] = sets;
  json["cardinality_L"] = c.cardinality;
  json["sampled"] = c.sampled;
  json["cap"] = cap;
  io::JsonValue pieces = io::JsonValue::array();
  for (Eigen::Index j = 0; j < c.subgradients.cols(); ++j) {
    io::JsonValue piece = io::JsonValue::object();
    piece["summary"] = c.piece_summaries[static_cast<std::size_t>(j)];
    piece["xi"] = Eigen::VectorXd(c.subgradients.col(j));
    piece["weight"] = c.clarke.weights.size() ? c.clarke.weights(j) : 0.0;
    pieces.push_back(piece);
  }
  json["pieces"] = pieces;
  json["default_piece_column"] = c.default_piece_column;
  json["scale_max_xi_norm"] = c.scale;
  io::JsonValue clarke = io::JsonValue::object();
  clarke["distance"] = c.clarke.distance;
  clarke["relative_distance"] = c.relative_distance;
  clarke["stationary"] = c.clarke_stationary;
  clarke["stationary_tolerance_relative"] = options.stationary_tolerance;
  clarke["distinct_subgradients"] = c.clarke.num_distinct_subgradients;
  if (c.clarke.subgradient_part.size()) {
    clarke["subgradient_part"] = c.clarke.subgradient_part;
    clarke["normal_cone_part"] = c.clarke.normal_part;
  }
  io::JsonValue active = io::JsonValue::array();
  for (const std::string& name : c.active_constraints) active.push_back(name);
  clarke["active_constraints"] = active;
  json["clarke"] = clarke;
  io::JsonValue single = io::JsonValue::object();
  single["distance"] = c.default_piece.distance;
  single["relative_distance"] = c.default_relative_distance;
  json["default_piece"] = single;
  io::JsonValue mf1 = io::JsonValue::object();
  mf1["computed"] = c.mf1.computed;
  mf1["rows"] = c.mf1.rows;
  mf1["cols"] = c.mf1.cols;
  mf1["extra_conditions_m0"] = c.mf1.extra_conditions;
  mf1["rank"] = c.mf1.rank;
  mf1["full_row_rank"] = c.mf1.full_row_rank;
  mf1["sigma_min_over_max"] = c.mf1.sigma_min / c.mf1.sigma_max;
  mf1["rank_tolerance_relative"] = options.rank_tolerance;
  mf1["spec_table_rows"] = c.mf1.spec_rows;
  mf1["spec_table_rank"] = c.mf1.spec_rank;
  mf1["spec_table_full_row_rank"] = c.mf1.spec_full_row_rank;
  json["mf1"] = mf1;
  io::JsonValue m = io::JsonValue::object();
  m["computed"] = c.mordukhovich.computed;
  m["message"] = c.mordukhovich.message;
  m["num_extreme_points"] = static_cast<std::int64_t>(c.mordukhovich.extreme.size());
  m["distance_delta_M"] = c.mordukhovich.distance;
  m["attaining_column"] = c.mordukhovich.attaining;
  m["clarke_minimizer_is_extreme"] = c.mordukhovich.clarke_minimizer_is_extreme;
  m["stationary"] = c.mordukhovich.stationary;
  json["mordukhovich"] = m;
  json["time_seconds"] = c.time_seconds;
  io::write_json(run_dir / "certificate.json", json);
  fmt::print("wrote {}\n", (run_dir / "certificate.json").string());
  return c.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

}  // namespace frictopt::app
