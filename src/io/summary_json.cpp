// SPDX-License-Identifier: MIT
#include "frictopt/io/summary_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "frictopt/linalg/blas_threads.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/study/load_change.hpp"

namespace frictopt::io {
namespace {

JsonValue status_fields(Status status, const std::string& message) {
  JsonValue j = JsonValue::object();
  j["status"] = std::string(to_string(status));
  j["message"] = message;
  return j;
}

JsonValue rows_of(const Eigen::MatrixXd& m) {
  JsonValue rows = JsonValue::array();
  for (Eigen::Index a = 0; a < m.rows(); ++a) rows.push_back(JsonValue(Eigen::VectorXd(m.row(a).transpose())));
  return rows;
}

JsonValue strings(const std::vector<std::string>& list) {
  JsonValue out = JsonValue::array();
  for (const std::string& s : list) out.push_back(s);
  return out;
}

JsonValue integers(const std::vector<int>& list) {
  JsonValue out = JsonValue::array();
  for (int i : list) out.push_back(i);
  return out;
}

}  // namespace

void add_members(JsonValue& into, const JsonValue& members) {
  for (const auto& [key, value] : members.as_object()) into[key] = value;
}

std::string cost_unit(const study::CostDefinition& cost, int dim) {
  const bool plane = dim == 2;
  // x^p: superscript digits for an integer exponent, "^p" otherwise.
  const auto power = [](const std::string& base, double p) {
    static const char* const digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
    if (p != std::floor(p) || p < 0.0 || p > 99.0) return fmt::format("{}^{:g}", base, p);
    const int n = static_cast<int>(p);
    return base + (n >= 10 ? std::string(digits[n / 10]) : std::string()) + digits[n % 10];
  };
  switch (cost.kind) {
    case cost::CostKind::kTargetPressure: return plane ? "N²/m²" : "N²";  // Σ(λ̄ − λ)²
    case cost::CostKind::kNormalForcePower: return power(plane ? "(N/m)" : "N", cost.exponent);
    case cost::CostKind::kCompliance:
    case cost::CostKind::kDissipation: return plane ? "J/m" : "J";  // work
    case cost::CostKind::kPressureNorm:  // (Σ a_i p_i^p)^{1/p}, a_i in m^{dim−1}
      return fmt::format("Pa·m^{:g}", (dim - 1) / cost.exponent);
    case cost::CostKind::kTotalSlip: return "m";
    case cost::CostKind::kTractionUniformity: return plane ? "Pa²·m" : "Pa²·m²";  // Σ a_i ‖t_i − t̄‖²
  }
  return "";
}

JsonValue to_json(const study::StateSummary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["relative_residual"] = s.relative_residual;
  j["assembly_seconds"] = s.assembly_seconds;
  j["factorization_seconds"] = s.factorization_seconds;
  j["solve_seconds"] = s.solve_seconds;
  return j;
}

JsonValue to_json(const contact::TrescaSolver::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["iterations"] = s.iterations;
  j["cg_steps"] = s.cg_steps;
  j["expansion_steps"] = s.expansion_steps;
  j["proportioning_steps"] = s.proportioning_steps;
  j["split_sweeps"] = s.split_sweeps;
  j["operator_applications"] = s.operator_applications;
  j["relative_projected_gradient"] = s.relative_projected_gradient;
  j["kkt_residual"] = s.kkt_residual;
  j["complementarity_gap"] = s.complementarity_gap;
  j["objective"] = s.objective;
  j["time_seconds"] = s.time_seconds;
  j["algorithm_given"] = std::string(contact::to_string(s.algorithm_given));
  j["algorithm_used"] = std::string(contact::to_string(s.algorithm_used));
  return j;
}

JsonValue to_json(const contact::CoulombSolver::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["fixed_point_iterations"] = s.iterations;
  j["qp_iterations"] = s.qp_iterations;
  j["operator_applications"] = s.operator_applications;
  j["inner_not_converged"] = s.inner_not_converged;
  j["last_relative_increment"] = s.last_relative_increment;
  j["kkt_residual"] = s.kkt_residual;
  j["complementarity_gap"] = s.complementarity_gap;
  j["time_seconds"] = s.time_seconds;
  j["method_given"] = std::string(contact::to_string(s.method_given));
  j["method_used"] = std::string(contact::to_string(s.method_used));
  return j;
}

JsonValue to_json(const contact::ContactResultants& r) {
  JsonValue j = JsonValue::object();
  j["total_normal_force"] = r.normal_force;
  j["total_tangential_force"] = Eigen::VectorXd(r.tangential_force.head(r.dim - 1));
  j["total_tangential_force_norm"] = r.tangential_force_norm;
  // The same total force in global axes (differs from the frame's components only on a tilted
  // [foundation]): the foundation's force on the body.
  j["total_force_global"] = Eigen::VectorXd(r.global_force.head(r.dim));
  j["tangential_to_normal_ratio"] = r.force_ratio;
  j["contact_area"] = r.contact_area;
  j["num_stick"] = r.num_stick;
  j["num_slip"] = r.num_slip;
  j["num_separated"] = r.num_separated;
  j["stick_area"] = r.stick_area;
  j["slip_area"] = r.slip_area;
  j["separated_area"] = r.separated_area;
  j["stick_centroid"] = Eigen::VectorXd(r.stick_centroid.head(r.dim - 1));
  j["stick_equivalent_radius"] = r.stick_equivalent_radius;
  j["contact_equivalent_radius"] = r.contact_equivalent_radius;
  return j;
}

JsonValue load_to_json(const contact::ContactResultants& r) {
  // The members of to_json(r) that describe the load (the stick zone's geometry left out).
  const JsonValue all = to_json(r);
  JsonValue j = JsonValue::object();
  for (const char* key : {"total_normal_force", "total_tangential_force", "total_tangential_force_norm",
                          "contact_area", "num_stick", "num_slip", "num_separated"})
    j[key] = all.at(key);
  return j;
}

JsonValue plates_to_json(const std::vector<fem::PlateReading>& plates) {
  JsonValue list = JsonValue::array();
  for (const fem::PlateReading& p : plates) {
    JsonValue j = JsonValue::object();
    j["part"] = p.boundary;
    JsonValue tied = JsonValue::array(), held = JsonValue::array();
    for (int c : p.tied) tied.push_back(fem::direction_name(c));
    for (int c : p.held) held.push_back(fem::direction_name(c));
    j["tied"] = tied;
    j["held"] = held;
    j["displacement"] = p.displacement;
    j["force"] = p.force;
    j["prescribed_force"] = p.prescribed;
    list.push_back(j);
  }
  return list;
}

std::string plates_report(const std::vector<fem::PlateReading>& plates) {
  std::string out;
  const auto vec = [](const Eigen::VectorXd& v) {
    std::string s = "[";
    for (Eigen::Index i = 0; i < v.size(); ++i) s += fmt::format("{}{:.6g}", i ? ", " : "", v(i));
    return s + "]";
  };
  for (const fem::PlateReading& p : plates)
    out += fmt::format("{}plate \"{}\": displacement {} m, force {} N (prescribed {} N)", out.empty() ? "" : "\n",
                       p.boundary, vec(p.displacement), vec(p.force), vec(p.prescribed));
  return out;
}

JsonValue load_comparison(study::ShapeOracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                          const Eigen::Ref<const Eigen::VectorXd>& initial_design) {
  JsonValue j = JsonValue::object();
  const study::Evaluation& final = oracle.evaluate_design(alpha, false);
  const contact::ContactResultants final_load = final.resultants;  // the cache may move on
  const std::vector<fem::PlateReading> final_plates = final.plates;
  const bool final_ok = final.ok;
  const study::Evaluation& initial = oracle.evaluate_design(initial_design, false);
  JsonValue warnings = JsonValue::array();
  if (final_ok && initial.ok) {
    for (const std::string& w : study::load_change_warnings(initial.resultants, final_load)) warnings.push_back(w);
    j["initial_load"] = load_to_json(initial.resultants);
    j["final_load"] = load_to_json(final_load);
    if (!final_plates.empty()) {
      j["initial_plates"] = plates_to_json(initial.plates);
      j["final_plates"] = plates_to_json(final_plates);
    }
  }
  j["warnings"] = std::move(warnings);
  j["load_warning_fraction"] = study::kLoadChangeWarningFraction;
  return j;
}

JsonValue to_json(const sensitivity::AdjointSensitivity::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["reciprocal_condition"] = s.reciprocal_condition;
  j["relative_residual"] = s.relative_residual;
  j["piece_residual"] = s.piece_residual;
  j["time_seconds"] = s.time_seconds;
  return j;
}

JsonValue to_json(const optim::BundleTrust::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  // Status kMaxIterations covers both limits (core::Status); this names the one that stopped.
  j["stopped_by"] = s.status == Status::kMaxIterations
                        ? std::string(s.evaluation_limit ? "max_evaluations" : "max_iterations")
                        : std::string(to_string(s.status));
  j["x"] = s.x;
  j["f"] = s.f;
  j["iterations"] = s.iterations;
  j["serious_steps"] = s.serious_steps;
  j["null_steps"] = s.null_steps;
  j["line_searches"] = s.line_searches;
  j["evaluations"] = s.evaluations;
  j["failed_evaluations"] = s.failed_evaluations;
  j["qp_solves"] = s.qp_solves;
  j["stationarity"] = s.stationarity;
  j["aggregate_error"] = s.aggregate_error;
  j["t"] = s.t;
  j["t_max_given"] = s.t_max_given;
  j["t_max_used"] = s.t_max_used;
  j["bundle_size_given"] = s.bundle_size_given;
  j["bundle_size_used"] = s.bundle_size_used;
  j["start_projected"] = s.start_projected;
  j["projection_distance"] = s.projection_distance;
  j["objective_scale"] = s.objective_scale;
  j["time_seconds"] = s.time_seconds;
  return j;
}

JsonValue to_json(const optim::ProjectedSubgradient::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["x"] = s.x;
  j["f"] = s.f;
  j["evaluations"] = s.evaluations;
  j["failed_evaluations"] = s.failed_evaluations;
  j["time_seconds"] = s.time_seconds;
  return j;
}

JsonValue to_json(const optim::DenseQpSolver::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["outcome"] = std::string(optim::to_string(s.outcome));
  j["x"] = s.x;
  j["multipliers_eq"] = s.multipliers_eq;
  j["multipliers_in"] = s.multipliers_in;
  j["active_inequalities"] = integers(s.active_inequalities);
  j["objective"] = s.objective;
  j["primal_infeasibility"] = s.primal_infeasibility;
  j["stationarity_residual"] = s.stationarity_residual;
  j["iterations"] = s.iterations;
  j["used_phase_one"] = s.used_phase_one;
  return j;
}

JsonValue to_json(const study::TribometerAngleResult& a, bool with_ramp) {
  JsonValue j = JsonValue::object();
  j["angle_degrees"] = a.angle_degrees;
  j["gross_sliding"] = a.gross_sliding;
  j["onset_step"] = a.onset_step + 1;  // 1-based, as the ramp CSV's step column
  j["onset_pull"] = a.onset_pull;
  j["onset_force"] = a.onset_force;
  j["onset_normal_force"] = a.onset_normal_force;
  j["steady_sliding"] = a.steady_sliding;
  j["sliding_force"] = a.sliding_force;
  j["sliding_normal_force"] = a.sliding_normal_force;
  j["sliding_resistance"] = a.sliding_resistance;
  j["law_resistance"] = a.law_resistance;
  j["force_angle_degrees"] = a.force_angle_degrees;
  j["slip_angle_degrees"] = a.slip_angle_degrees;
  j["measured_mu"] = a.measured_coefficient;
  j["law_mu"] = a.law_coefficient;
  j["relative_error"] = a.coefficient_error;
  j["normality_residual"] = a.normality_residual;
  if (with_ramp) {
    JsonValue ramp = JsonValue::array();
    for (const study::TribometerRampPoint& pt : a.ramp) {
      JsonValue r = JsonValue::object();
      r["pull"] = pt.pull;
      r["normal_force"] = pt.normal_force;
      r["tangential_force"] = Eigen::VectorXd(pt.tangential_force);
      r["stick_fraction"] = pt.stick_fraction;
      r["num_stick"] = pt.num_stick;
      r["num_slip"] = pt.num_slip;
      ramp.push_back(std::move(r));
    }
    j["ramp"] = std::move(ramp);
  }
  return j;
}

JsonValue to_json(const study::LoadingProgram::Summary& summary) {
  JsonValue json = JsonValue::object();
  json["status"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  json["steps_solved"] = summary.steps_solved;
  json["factorizations"] = summary.factorizations;
  json["factorization_seconds"] = summary.factorization_seconds;
  json["contact_seconds"] = summary.contact_seconds;
  json["time_seconds"] = summary.time_seconds;
  return json;
}

JsonValue to_json(const study::Tribometer::Summary& s) {
  JsonValue j = JsonValue::object();
  j["status"] = std::string(to_string(s.status));
  j["message"] = s.message;
  j["press_displacement"] = s.press_displacement;
  j["press_iterations"] = s.press_iterations;
  j["pull_displacement"] = s.pull_displacement;  // the ramp's final pull, the case's or the automatic one
  j["automatic_pull"] = s.automatic_pull;
  j["contact_solves"] = s.contact_solves;
  j["factorizations"] = s.factorizations;
  j["time_seconds"] = s.time_seconds;
  JsonValue angles = JsonValue::array();
  for (const study::TribometerAngleResult& a : s.angles) angles.push_back(to_json(a));
  j["angles"] = std::move(angles);
  return j;
}

JsonValue to_json(const study::Identification::Summary& s) {
  JsonValue j = status_fields(s.status, s.message);
  j["ceres_brief_report"] = s.ceres_brief_report;
  j["iterations"] = s.iterations;
  j["state_solves"] = s.state_solves;
  j["jacobian_evaluations"] = s.jacobian_evaluations;
  j["initial_cost"] = s.initial_cost;
  j["final_cost"] = s.final_cost;
  j["chi_square"] = s.chi_square;
  j["degrees_of_freedom"] = s.degrees_of_freedom;
  j["time_seconds"] = s.time_seconds;
  j["index_sets"] = s.index_sets;
  JsonValue estimates = JsonValue::array();
  for (const auto& e : s.estimates) {
    JsonValue item = JsonValue::object();
    item["name"] = e.name;
    item["initial"] = e.initial;
    item["value"] = e.value;
    item["lower"] = e.lower;
    item["upper"] = e.upper;
    item["standard_deviation"] = e.standard_deviation;
    item["identifiability"] = std::string(study::to_string(e.identifiability));
    item["note"] = e.note;
    estimates.push_back(item);
  }
  j["estimates"] = estimates;
  j["covariance"] = rows_of(s.covariance);
  j["correlation"] = rows_of(s.correlation);
  j["singular_values"] = s.singular_values;
  JsonValue experiments = JsonValue::array();
  for (const auto& x : s.experiments) {
    JsonValue item = JsonValue::object();
    item["name"] = x.name;
    item["first_measurement"] = static_cast<std::int64_t>(x.first_measurement);
    item["measurements"] = static_cast<std::int64_t>(x.num_measurements);
    item["chi_square"] = x.chi_square;
    item["rms_residual"] = x.rms_residual;
    item["slipping_nodes"] = x.num_slipping_nodes;
    item["index_sets"] = x.index_sets;
    experiments.push_back(item);
  }
  j["experiments"] = experiments;
  return j;
}

JsonValue to_json(const study::Certificate& c, const study::CertifyOptions& options) {
  JsonValue json = status_fields(c.status, c.message);
  json["alpha"] = c.alpha;
  json["value"] = c.value;
  JsonValue sets = JsonValue::object();
  sets["summary"] = c.index_sets.summary();
  sets["weak_nodes"] = c.index_sets.num_weak_nodes();
  for (auto n : {sensitivity::NormalSet::kStrongContact, sensitivity::NormalSet::kNoContact,
                 sensitivity::NormalSet::kWeakContact})
    sets[sensitivity::to_string(n)] = c.index_sets.count(n);
  JsonValue tangential = JsonValue::object();
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
  json["cap"] = options.cap;
  // A cost along a loading history (docs/theory/history-adjoint.md §4): each step's index sets and
  // |L_k|.
  if (!c.history_steps.empty()) {
    JsonValue steps = JsonValue::array();
    for (const std::string& line : c.history_steps) steps.push_back(line);
    json["history_steps"] = steps;
  }
  JsonValue pieces = JsonValue::array();
  for (Eigen::Index j = 0; j < c.subgradients.cols(); ++j) {
    JsonValue piece = JsonValue::object();
    piece["summary"] = c.piece_summaries[static_cast<std::size_t>(j)];
    piece["xi"] = Eigen::VectorXd(c.subgradients.col(j));
    piece["weight"] = c.clarke.weights.size() ? c.clarke.weights(j) : 0.0;
    pieces.push_back(piece);
  }
  json["pieces"] = pieces;
  json["default_piece_column"] = c.default_piece_column;
  json["scale_max_xi_norm"] = c.scale;
  JsonValue clarke = JsonValue::object();
  clarke["distance"] = c.clarke.distance;
  clarke["relative_distance"] = c.relative_distance;
  clarke["stationary"] = c.clarke_stationary;
  clarke["stationary_tolerance_relative"] = options.stationary_tolerance;
  clarke["distinct_subgradients"] = c.clarke.num_distinct_subgradients;
  if (c.clarke.subgradient_part.size()) {
    clarke["subgradient_part"] = c.clarke.subgradient_part;
    clarke["normal_cone_part"] = c.clarke.normal_part;
  }
  clarke["active_constraints"] = strings(c.active_constraints);
  json["clarke"] = clarke;
  JsonValue single = JsonValue::object();
  single["distance"] = c.default_piece.distance;
  single["relative_distance"] = c.default_relative_distance;
  json["default_piece"] = single;
  JsonValue mf1 = JsonValue::object();
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
  JsonValue m = JsonValue::object();
  m["computed"] = c.mordukhovich.computed;
  m["message"] = c.mordukhovich.message;
  m["num_extreme_points"] = static_cast<std::int64_t>(c.mordukhovich.extreme.size());
  m["distance_delta_M"] = c.mordukhovich.distance;
  m["attaining_column"] = c.mordukhovich.attaining;
  m["clarke_minimizer_is_extreme"] = c.mordukhovich.clarke_minimizer_is_extreme;
  m["stationary"] = c.mordukhovich.stationary;
  json["mordukhovich"] = m;
  if (c.goldstein.computed) {
    // "goldstein": the sampled certificate ("sampled" above says whether 𝕃 was sampled).
    JsonValue sampled = JsonValue::object();
    sampled["radius"] = c.goldstein.radius;
    sampled["requested"] = c.goldstein.requested;
    sampled["evaluated"] = c.goldstein.evaluated;
    sampled["skipped"] = c.goldstein.failed;
    sampled["largest_step"] = c.goldstein.largest_step;
    sampled["distance"] = c.goldstein.clarke.distance;
    sampled["relative_distance"] = c.goldstein.relative_distance;
    sampled["stationary"] = c.goldstein.stationary;
    sampled["message"] = c.goldstein.message;
    json["goldstein"] = sampled;
  }
  json["time_seconds"] = c.time_seconds;
  return json;
}

JsonValue run_environment() {
  JsonValue j = JsonValue::object();
  // With the default (automatic) BLAS thread count the summation order follows the machine's
  // load, so a record says which policy its round-off was produced under.
  j["blas_threads"] = linalg::describe_blas_threads();
  // The BLAS CHOLMOD and LAPACK actually reach: its speed, and its round-off, are the run's.
  j["blas"] = linalg::describe_loaded_blas();
  return j;
}

JsonValue design_chart(const study::ElasticBody& body) {
  const study::BodyDefinition& d = body.definition();
  const shape::BezierShape& shape = d.shape;
  const int dim = shape.dim();
  // The chart's frame: the foundation frame of an imported body's patch, else the box's own axes
  // (x1, x2 in-plane, the height x_dim; the Bézier surface is the box's bottom).
  mesh::PlaneFrame frame = mesh::PlaneFrame::standard(dim);
  Eigen::VectorXd origin = Eigen::VectorXd::Zero(dim - 1);
  JsonValue j = JsonValue::object();
  if (d.imported_mesh) {
    const mesh::DesignMotion& motion = d.imported_mesh->motion;
    if (motion.frame.normal.size() == dim) frame = motion.frame;
    origin = mesh::patch_chart(*d.imported_mesh->reference, motion.patch, frame).origin;
    j["patch"] = motion.patch;
  } else {
    j["patch"] = d.contact_surface;
  }
  const auto [m1, m2] = shape.control_net();
  const auto [a, b] = shape.extents();
  j["origin"] = origin;                                                      // [m], in the plane coordinates
  j["extents"] = dim == 3 ? Eigen::VectorXd(Eigen::Vector2d(a, b)) : Eigen::VectorXd::Constant(1, a);  // [m]
  JsonValue controls = JsonValue::array(), degree = JsonValue::array(), tangents = JsonValue::array();
  for (int c = 0; c < dim - 1; ++c) {
    const int m = c == 0 ? m1 : m2;
    controls.push_back(m);
    degree.push_back(m - 1);
    tangents.push_back(Eigen::VectorXd(frame.tangents.col(c)));
  }
  j["control_points"] = controls;
  j["degree"] = degree;
  j["normal"] = frame.normal;
  j["tangents"] = tangents;
  j["formula"] = dim == 3 ? "G(x') = sum_{i,j} alpha[i + m1*j] B_i^{m1-1}((x'_1 - origin_1)/a) "
                            "B_j^{m2-1}((x'_2 - origin_2)/b), x'_c = tangents[c] . x; the patch moves by G along normal"
                          : "G(x') = sum_i alpha[i] B_i^{m1-1}((x'_1 - origin_1)/a), x'_1 = tangents[0] . x; the patch "
                            "moves by G along normal";
  return j;
}

JsonValue solve_summary(const std::string& case_name, const study::ElasticBody& body, const study::BodyState& state) {
  const auto& mesh = body.mesh();
  JsonValue summary = JsonValue::object();
  summary["case"] = case_name;
  summary["command"] = "solve";
  add_members(summary, run_environment());
  add_members(summary, to_json(state.summary));
  summary["dim"] = mesh.dim();
  summary["element"] = std::string(mesh::to_string(mesh.element_kind()));
  summary["num_elements"] = static_cast<std::int64_t>(mesh.num_elements());
  summary["min_scaled_jacobian"] = mesh.min_scaled_jacobian(state.positions);
  summary["num_nodes"] = static_cast<std::int64_t>(mesh.num_nodes());
  summary["num_unknowns"] = static_cast<std::int64_t>(body.elasticity().dofs().num_free());
  summary["alpha"] = state.alpha;
  if (state.contact) {
    const auto& c = *state.contact;
    JsonValue contact = to_json(c.summary);
    contact["num_contact_nodes"] = static_cast<std::int64_t>(c.state.num_nodes());
    contact["dense_delassus"] = c.dense_delassus;
    add_members(contact, to_json(c.resultants));
    contact["min_initial_gap"] = c.gaps.size() ? c.gaps.minCoeff() : 0.0;
    if (c.floating) {
      JsonValue f = status_fields(c.floating->status, c.floating->message);
      // Which method produced the state: Newton on (z, β), the augmented Lagrangian (also after a
      // failed Newton attempt, whose steps newton_iterations counts), or none (a load refused
      // before solving, beyond the friction capacity).
      f["method"] = c.floating->solved_by_newton        ? "semismooth_newton"
                    : c.floating->outer_iterations > 0 ? "augmented_lagrangian"
                                                       : "none";
      f["newton_iterations"] = c.floating->newton_iterations;
      f["outer_iterations"] = c.floating->outer_iterations;
      f["fixed_point_iterations"] = c.floating->fixed_point_iterations;
      f["qp_iterations"] = c.floating->qp_iterations;
      f["equality_residual"] = c.floating->equality_residual;
      f["penalty"] = c.floating->penalty;
      f["rigid_motion"] = c.rigid_motion;
      f["time_seconds"] = c.floating->time_seconds;
      contact["floating"] = f;
    }
    summary["contact"] = contact;
  }
  if (!state.plates.empty()) summary["plates"] = plates_to_json(state.plates);
  if (state.summary.status != Status::kConverged) return summary;  // no energies of a failed state
  summary["strain_energy"] = state.strain_energy;
  summary["external_work"] = state.external_work;
  summary["volume"] = state.volume;
  summary["max_von_mises"] = state.stress.nodal_von_mises.maxCoeff();
  return summary;
}

}  // namespace frictopt::io
