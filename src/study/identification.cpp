// SPDX-License-Identifier: MIT
#include "frictopt/study/identification.hpp"

#include <ceres/ceres.h>
#include <ceres/covariance.h>
#include <fmt/format.h>

#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/fem/node_selection.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/sensitivity/index_sets.hpp"
#include "frictopt/sensitivity/parameter_sensitivity.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/derivative_accuracy.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {
namespace {

// One table per enum (core/enum_table.hpp): the spellings of measurement files, case files and
// reports.
constexpr auto kQuantities = frictopt::detail::make_enum_table<MeasuredQuantity>(
    std::pair{MeasuredQuantity::kNormalForce, "normal_force"}, std::pair{MeasuredQuantity::kPressure, "pressure"},
    std::pair{MeasuredQuantity::kTangentialForceX1, "tangential_force_x1"},
    std::pair{MeasuredQuantity::kTangentialForceX2, "tangential_force_x2"},
    std::pair{MeasuredQuantity::kTractionX1, "traction_x1"}, std::pair{MeasuredQuantity::kTractionX2, "traction_x2"},
    std::pair{MeasuredQuantity::kSlipX1, "slip_x1"}, std::pair{MeasuredQuantity::kSlipX2, "slip_x2"},
    std::pair{MeasuredQuantity::kTotalNormalForce, "total_normal_force"},
    std::pair{MeasuredQuantity::kTotalTangentialForceX1, "total_tangential_force_x1"},
    std::pair{MeasuredQuantity::kTotalTangentialForceX2, "total_tangential_force_x2"});

constexpr auto kLosses = frictopt::detail::make_enum_table<RobustLoss>(
    std::pair{RobustLoss::kNone, "none"}, std::pair{RobustLoss::kHuber, "huber"}, std::pair{RobustLoss::kCauchy, "cauchy"});

constexpr auto kIdentifiability = frictopt::detail::make_enum_table<Identifiability>(
    std::pair{Identifiability::kDetermined, "determined"}, std::pair{Identifiability::kAtBound, "at_bound"},
    std::pair{Identifiability::kNotDetermined, "not_determined"}, std::pair{Identifiability::kCorrelated, "correlated"});

// Tangential component (0 or 1) of a quantity, or −1 for normal quantities.
int tangential_component(MeasuredQuantity q) {
  switch (q) {
    case MeasuredQuantity::kTangentialForceX1:
    case MeasuredQuantity::kTractionX1:
    case MeasuredQuantity::kSlipX1:
    case MeasuredQuantity::kTotalTangentialForceX1: return 0;
    case MeasuredQuantity::kTangentialForceX2:
    case MeasuredQuantity::kTractionX2:
    case MeasuredQuantity::kSlipX2:
    case MeasuredQuantity::kTotalTangentialForceX2: return 1;
    default: return -1;
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format_point(const Eigen::VectorXd& x) {
  std::string s = "(";
  for (Eigen::Index k = 0; k < x.size(); ++k) s += fmt::format("{}{:g}", k ? ", " : "", x(k));
  return s + ")";
}

// The input that fixes a component of mesh node `node` (for messages): "dirichlet[k] (face ...)"
// or "constraint[k]", the first that selects the node.
std::string what_fixes(const BodyDefinition& definition, const mesh::Mesh& mesh, int node) {
  for (std::size_t k = 0; k < definition.dirichlet.size(); ++k) {
    const fem::FaceDirichlet& d = definition.dirichlet[k];
    if (!mesh.has_boundary(d.boundary)) continue;
    const std::vector<int>& nodes = mesh.boundary(d.boundary).nodes;
    if (std::find(nodes.begin(), nodes.end(), node) != nodes.end())
      return fmt::format("dirichlet[{}] (face \"{}\")", k, d.boundary);
  }
  for (std::size_t k = 0; k < definition.constraints.size(); ++k) {
    const std::string field = fmt::format("constraint[{}]", k);
    const std::vector<int> nodes = fem::select_nodes(mesh, definition.constraints[k].where, field);
    if (std::binary_search(nodes.begin(), nodes.end(), node)) return field;
  }
  return "a [[dirichlet]] table or a [[constraint]]";
}

}  // namespace

std::string_view to_string(MeasuredQuantity quantity) { return kQuantities.name(quantity); }

MeasuredQuantity parse_measured_quantity(std::string_view text) {
  if (const auto q = kQuantities.find(text)) return *q;
  throw InvalidInput(fmt::format("quantity = \"{}\"; expected one of {}", text, kQuantities.spellings()));
}

bool is_total(MeasuredQuantity q) {
  return q == MeasuredQuantity::kTotalNormalForce || q == MeasuredQuantity::kTotalTangentialForceX1 ||
         q == MeasuredQuantity::kTotalTangentialForceX2;
}

std::string_view to_string(RobustLoss loss) { return kLosses.name(loss); }

RobustLoss parse_robust_loss(std::string_view text) {
  if (const auto l = kLosses.find(text)) return *l;
  throw InvalidInput(fmt::format("loss = \"{}\"; expected one of {}", text, kLosses.spellings()));
}

std::string_view to_string(Identifiability identifiability) { return kIdentifiability.name(identifiability); }

void Identification::Options::validate() const {
  const auto fail = [](std::string_view field, const std::string& value, std::string_view expected) {
    throw InvalidInput(fmt::format("Identification::Options::{} = {}; expected {}", field, value, expected));
  };
  if (parameters.empty()) fail("parameters", "[]", "at least one parameter to identify");
  std::set<std::string> seen;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const ParameterSpec& p = parameters[k];
    const std::string field = fmt::format("parameters[{}] ({})", k, p.name);
    if (!seen.insert(p.name).second) fail(field + ".name", p.name, "distinct parameter names");
    if (!(std::isfinite(p.lower) && std::isfinite(p.upper)))
      fail(field, fmt::format("[{}, {}]", p.lower, p.upper), "finite bounds");
    if (!(p.lower <= p.upper))
      fail(field, fmt::format("lower {} > upper {}", p.lower, p.upper), "lower <= upper");
    if (p.name == "young" ? !(p.lower > 0) : !(p.lower >= 0))
      fail(field + ".lower", fmt::format("{}", p.lower), p.name == "young" ? "> 0" : ">= 0");
    if (!std::isnan(p.initial) && !(p.initial >= p.lower && p.initial <= p.upper))
      fail(field + ".initial", fmt::format("{}", p.initial), fmt::format("within [{}, {}]", p.lower, p.upper));
  }
  if (!(loss_scale > 0 && std::isfinite(loss_scale))) fail("loss_scale", fmt::format("{}", loss_scale), "> 0");
  if (max_iterations < 1) fail("max_iterations", fmt::format("{}", max_iterations), ">= 1");
  if (!(function_tolerance > 0)) fail("function_tolerance", fmt::format("{}", function_tolerance), "> 0");
  if (!(parameter_tolerance > 0)) fail("parameter_tolerance", fmt::format("{}", parameter_tolerance), "> 0");
  if (!(gradient_tolerance > 0)) fail("gradient_tolerance", fmt::format("{}", gradient_tolerance), "> 0");
  if (!(state_tolerance > 0 && state_tolerance < 1)) fail("state_tolerance", fmt::format("{}", state_tolerance), "in (0, 1)");
  if (!(zero_column_tolerance > 0)) fail("zero_column_tolerance", fmt::format("{}", zero_column_tolerance), "> 0");
  if (!(rank_tolerance > 0 && rank_tolerance < 1)) fail("rank_tolerance", fmt::format("{}", rank_tolerance), "in (0, 1)");
}

std::string Identification::Summary::brief_report() const {
  std::string params;
  for (const ParameterEstimate& e : estimates)
    params += fmt::format("{}{} = {:.6g}{}", params.empty() ? "" : ", ", e.name, e.value,
                          std::isnan(e.standard_deviation) ? std::string(" (") + std::string(to_string(e.identifiability)) + ")"
                                                           : fmt::format(" ± {:.2g}", e.standard_deviation));
  return fmt::format("identification: {} ({}); {} iterations, {} state solves, cost {:.6e} -> {:.6e}, chi² {:.4g} "
                     "({} dof); {}; {:.2f} s",
                     frictopt::to_string(status), message, iterations, state_solves, initial_cost, final_cost,
                     chi_square, degrees_of_freedom, params, time_seconds);
}

// ------------------------------------------------------------------------------------------
// The model: the body's contact problem in contact space (docs/theory/state-problem.md §5):
// z solves the Coulomb problem with M(E) = (E₀/E) M₀ and c(E) = (E₀/E) c_traction + c_dirichlet
// + (0, g): A(E) = (E/E₀) A₀ and the Dirichlet lifting −A_fd u_d scales with E, the tractions do not.

// One experiment's model: its body (the case's at the initial design, with the experiment's
// loads and turned law), its contact-space operators and its measurement rows.
struct ExperimentModel {
  std::string name;
  double orientation = 0.0;
  BodyDefinition definition;
  std::unique_ptr<ElasticBody> body;
  contact::FrictionLaw law0 = contact::FrictionLaw::disc(0.0);  // the case's law turned by `orientation`
  int dim = 3;
  Eigen::Index num_nodes = 0;
  std::shared_ptr<const Eigen::MatrixXd> M0;       // M at E₀, dense (shared with the state solve)
  std::unique_ptr<contact::DenseDelassus> M0_op;   // products with M0 (dsymv)
  Eigen::VectorXd c_traction, c_dirichlet, gap_vector;  // gap_vector = (0, g) per node
  std::optional<contact::ContactState> warm_start;
  Eigen::SparseMatrix<double> Lz, Lg;  // its predictions = Lz z + Lg ∇
  Eigen::Index first_row = 0, num_rows = 0;  // its rows among all measurements
  // The last trial point's state and law (for the Jacobian and the lower-bound report).
  bool solved = false;
  int num_slipping_nodes = 0;
  std::string index_sets;
};

struct Identification::Impl {
  BodyDefinition definition;  // the case's own
  Options options;
  std::vector<Measurement> measurements;  // all experiments' rows, in order
  std::vector<int> measurement_experiment;
  std::vector<std::string> experiment_names;
  std::vector<ExperimentModel> experiments;
  std::vector<std::string> names;
  std::vector<int> friction_index;  // per identified parameter: index into the law's parameters, −1 = young
  contact::FrictionLaw law0 = contact::FrictionLaw::disc(0.0);  // the case's law (unturned)
  Eigen::VectorXd friction_values0;
  double young0 = 0.0;
  Eigen::VectorXd initial, scale;
  contact::CoulombSolver::Options coulomb;
  // Cache of the last trial point (Ceres evaluates every residual block at the same point).
  Eigen::VectorXd cached_parameters;
  std::optional<Prediction> cached;
  int state_solves = 0, jacobian_evaluations = 0;

  void setup_parameters();
  void setup_contact(ExperimentModel& e);
  void resolve_measurements(ExperimentModel& e);
  const Prediction& predict(const Eigen::VectorXd& p, bool with_jacobian);
  bool add_jacobian(ExperimentModel& e, const Eigen::VectorXd& p, Prediction& out);
  contact::FrictionLaw law_for(const contact::FrictionLaw& base, const Eigen::VectorXd& p) const;
  contact::FrictionLaw law_for(const Eigen::VectorXd& p) const { return law_for(law0, p); }
  double young_for(const Eigen::VectorXd& p) const;
};

void Identification::Impl::setup_parameters() {
  law0 = definition.contact->law;
  young0 = definition.material.young;
  const sensitivity::FrictionParameters fp = sensitivity::friction_parameters(law0);
  friction_values0 = fp.values;
  std::string accepted;
  for (const std::string& n : fp.names) accepted += n + ", ";
  accepted += "young";
  const Eigen::Index n = static_cast<Eigen::Index>(options.parameters.size());
  initial.resize(n);
  scale.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const ParameterSpec& spec = options.parameters[static_cast<std::size_t>(k)];
    names.push_back(spec.name);
    double case_value;
    if (spec.name == "young") {
      friction_index.push_back(-1);
      case_value = young0;
    } else {
      const auto it = std::find(fp.names.begin(), fp.names.end(), spec.name);
      if (it == fp.names.end())
        throw InvalidInput(fmt::format("identification parameter \"{}\" is not a parameter of the law {}; expected one of {}",
                                       spec.name, law0.describe(), accepted));
      const int index = static_cast<int>(it - fp.names.begin());
      friction_index.push_back(index);
      case_value = fp.values(index);
    }
    initial(k) = std::isnan(spec.initial) ? case_value : spec.initial;
    if (!(initial(k) >= spec.lower && initial(k) <= spec.upper))
      throw InvalidInput(fmt::format("identification parameter \"{}\": initial value {} (the case's value) is outside "
                                     "[{}, {}]; give an initial value within the bounds",
                                     spec.name, initial(k), spec.lower, spec.upper));
    // Ceres works on p/scale, O(1) for coefficients and moduli alike.
    scale(k) = initial(k) != 0.0 ? std::abs(initial(k)) : std::max({std::abs(spec.lower), std::abs(spec.upper), 1e-300});
  }
  // Ceres evaluates on the bounds: the law must exist there (a polygon or an elliptic n-gon has
  // no single zero coefficient, unlike the isotropic μ = 0 of a frictionless law).
  for (Eigen::Index k = 0; k < n; ++k) {
    const ParameterSpec& spec = options.parameters[static_cast<std::size_t>(k)];
    if (friction_index[static_cast<std::size_t>(k)] < 0) continue;
    Eigen::VectorXd at_bound = initial;
    at_bound(k) = spec.lower;
    try {
      (void)law_for(at_bound);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("identification parameter \"{}\": lower bound {} gives no valid friction law ({}); "
                                     "expected a lower bound > 0 for this law",
                                     spec.name, spec.lower, e.what()));
    }
  }
}

void Identification::Impl::setup_contact(ExperimentModel& e) {
  ElasticBody& body = *e.body;
  // The FE problem does not depend on the parameters except through E (a scalar factor):
  // assemble, factorize and build M once, from a state solve at the case's parameters.
  // Its contact problem without the floating body's equilibrium rows (docs/theory/loading-plate.md §3).
  if (body.num_floating_modes() > 0)
    throw InvalidInput(fmt::format("identification: the body floats ({} rigid-body modes held by contact only); "
                                   "expected Dirichlet conditions that hold it",
                                   body.num_floating_modes()));
  const BodyState s = body.solve(e.definition.initial_design, "initial design");
  if (!s.contact)
    throw InvalidInput("identification: the elasticity problem at the initial design could not be factorized: " +
                       s.summary.message);
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const fem::LinearElasticity& fem = body.elasticity();
  e.dim = boundary.dim();
  e.num_nodes = boundary.num_nodes();
  if (e.num_nodes == 0) {
    // A node of Γ_c with a fixed component is a support, not a contact node (docs/theory/problem.md
    // §3): with every node fixed there is no contact force to measure and no friction to identify.
    const mesh::BoundarySet& surface = body.mesh().boundary(e.definition.contact_surface);
    throw InvalidInput(fmt::format(
        "identification: the contact surface \"{}\" has no contact node: each of its {} nodes has a component "
        "fixed by a [[dirichlet]] table or a [[constraint]] ({} fixes node {}), and a fixed node is a support, not a "
        "contact node; expected free nodes on the contact surface (remove that constraint or select fewer nodes)",
        e.definition.contact_surface, surface.nodes.size(),
        surface.nodes.empty() ? std::string("none") : what_fixes(e.definition, body.mesh(), surface.nodes.front()),
        surface.nodes.empty() ? -1 : surface.nodes.front()));
  }
  // The constructor refuses the engines that do not form the dense M (the PETSc engine's is a
  // Krylov operator): a state without it is a defect, reported rather than dereferenced.
  if (!s.contact->delassus_matrix)
    throw NumericalFailure(fmt::format("identification: the {} engine's state has no dense Delassus matrix; the "
                                       "identification needs it",
                                       body.engine().name()));
  e.M0 = s.contact->delassus_matrix;
  e.M0_op = std::make_unique<contact::DenseDelassus>(e.M0);
  const Eigen::VectorXd l_traction = fem.dofs().restrict_forces(fem.traction_load(s.positions));
  const Eigen::VectorXd l_lift = fem.load() - l_traction;
  e.c_traction = boundary.times(fem.factorization().solve(l_traction));
  e.c_dirichlet = boundary.times(fem.factorization().solve(l_lift));
  e.gap_vector = Eigen::VectorXd::Zero(boundary.num_unknowns());
  for (Eigen::Index i = 0; i < e.num_nodes; ++i) e.gap_vector(e.dim * i + e.dim - 1) = s.contact->gaps(i);
  if (s.contact->summary.converged()) e.warm_start = s.contact->state;
}

void Identification::Impl::resolve_measurements(ExperimentModel& e) {
  const ElasticBody& body = *e.body;
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const Eigen::MatrixXd& plane = boundary.plane_coordinates();
  const Eigen::VectorXd& areas = boundary.tributary_areas();
  const int dim = e.dim;
  const Eigen::Index p = e.num_nodes, m = dim * p;
  // Node spacing: the largest nearest-neighbour distance (a point on Γ_c is within it of a node).
  double spacing = 0.0;
  for (Eigen::Index i = 0; i < p; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < p; ++j)
      if (j != i) nearest = std::min(nearest, (plane.row(i) - plane.row(j)).norm());
    if (std::isfinite(nearest)) spacing = std::max(spacing, nearest);
  }
  // The nodes of Γ_c that a [[dirichlet]] table or a [[constraint]] fixes are supports, not
  // contact nodes: their in-plane coordinates (in the foundation's frame, as plane_coordinates),
  // so that a location nearest to one of them is refused instead of moved to a contact neighbour.
  std::vector<int> fixed_nodes;
  Eigen::MatrixXd fixed_plane;
  {
    const mesh::Mesh& mesh = body.mesh();
    const std::vector<int>& contact_nodes = boundary.nodes();
    const std::set<int> free(contact_nodes.begin(), contact_nodes.end());
    for (const int node : mesh.boundary(e.definition.contact_surface).nodes)
      if (free.count(node) == 0) fixed_nodes.push_back(node);
    fixed_plane.resize(static_cast<Eigen::Index>(fixed_nodes.size()), dim - 1);
    for (std::size_t k = 0; k < fixed_nodes.size(); ++k) {
      const Eigen::RowVectorXd X = mesh.reference_positions().row(fixed_nodes[k]);
      fixed_plane.row(static_cast<Eigen::Index>(k)) =
          boundary.standard_foundation() ? Eigen::RowVectorXd(X.head(dim - 1))
                                         : Eigen::RowVectorXd(X * boundary.foundation().frame.tangents);
    }
  }
  std::vector<Eigen::Triplet<double>> tz, tg;
  for (Eigen::Index r = 0; r < e.num_rows; ++r) {
    Measurement& meas = measurements[static_cast<std::size_t>(e.first_row + r)];
    const std::string where = meas.label.empty() ? fmt::format("measurement {}", e.first_row + r) : meas.label;
    const int c = tangential_component(meas.quantity);
    if (dim == 2 && c == 1)
      throw InvalidInput(fmt::format("{}: quantity = {}; expected a 2D quantity (x1 components only) for this 2D case",
                                     where, to_string(meas.quantity)));
    if (!(std::isfinite(meas.value)))
      throw InvalidInput(fmt::format("{}: value = {}; expected a finite number", where, meas.value));
    if (!(meas.sigma > 0 && std::isfinite(meas.sigma)))
      throw InvalidInput(fmt::format("{}: sigma = {}; expected a standard deviation > 0", where, meas.sigma));
    const auto row = static_cast<int>(r);
    if (is_total(meas.quantity)) {
      if (meas.node >= 0 || meas.point)
        throw InvalidInput(fmt::format("{}: quantity {} is a sum over all contact nodes; expected no node or location",
                                       where, to_string(meas.quantity)));
      for (Eigen::Index i = 0; i < p; ++i) {
        if (c < 0) tz.emplace_back(row, dim * i + dim - 1, 1.0);
        else tz.emplace_back(row, dim * i + c, -1.0);  // τ = −q
      }
      continue;
    }
    if (meas.point) {
      if (meas.point->size() != dim - 1)
        throw InvalidInput(fmt::format("{}: location {} has {} coordinate(s); expected {} (x1{}) in {}D", where,
                                       format_point(*meas.point), meas.point->size(), dim - 1, dim == 3 ? ", x2" : "",
                                       dim));
      Eigen::Index best = 0;
      const double distance = (plane.rowwise() - meas.point->transpose()).rowwise().norm().minCoeff(&best);
      if (!(distance <= spacing))
        throw InvalidInput(fmt::format("{}: location {} is {:.4g} m from the nearest contact node (node {} at {}); "
                                       "expected a point on the contact surface, within one node spacing ({:.4g} m)",
                                       where, format_point(*meas.point), distance, best,
                                       format_point(plane.row(best).transpose()), spacing));
      if (fixed_plane.rows() > 0) {
        Eigen::Index fixed = 0;
        const double to_fixed = (fixed_plane.rowwise() - meas.point->transpose()).rowwise().norm().minCoeff(&fixed);
        const int node = fixed_nodes[static_cast<std::size_t>(fixed)];
        if (to_fixed < distance)
          throw InvalidInput(fmt::format(
              "{}: location {} is nearest to mesh node {} at {}, which {} fixes: a support, not a contact node, so "
              "no contact force or slip is computed there; expected a location nearest to a free contact node "
              "(the nearest is contact node {} at {}, {:.4g} m away)",
              where, format_point(*meas.point), node, format_point(fixed_plane.row(fixed).transpose()),
              what_fixes(e.definition, body.mesh(), node), best, format_point(plane.row(best).transpose()), distance));
      }
      meas.node = static_cast<int>(best);
    } else if (meas.node < 0 || meas.node >= p) {
      throw InvalidInput(fmt::format("{}: node = {}; expected a contact node index in [0, {}) or a location", where,
                                     meas.node, p));
    }
    const Eigen::Index i = meas.node;
    const double inv_area = 1.0 / areas(i);
    switch (meas.quantity) {
      case MeasuredQuantity::kNormalForce: tz.emplace_back(row, dim * i + dim - 1, 1.0); break;
      case MeasuredQuantity::kPressure: tz.emplace_back(row, dim * i + dim - 1, inv_area); break;
      case MeasuredQuantity::kTangentialForceX1:
      case MeasuredQuantity::kTangentialForceX2: tz.emplace_back(row, dim * i + c, -1.0); break;
      case MeasuredQuantity::kTractionX1:
      case MeasuredQuantity::kTractionX2: tz.emplace_back(row, dim * i + c, -inv_area); break;
      case MeasuredQuantity::kSlipX1:
      case MeasuredQuantity::kSlipX2: tg.emplace_back(row, dim * i + c, -1.0); break;  // u_t = −∇_q
      default: break;
    }
  }
  e.Lz.resize(e.num_rows, m);
  e.Lz.setFromTriplets(tz.begin(), tz.end());
  e.Lg.resize(e.num_rows, m);
  e.Lg.setFromTriplets(tg.begin(), tg.end());
}

contact::FrictionLaw Identification::Impl::law_for(const contact::FrictionLaw& base, const Eigen::VectorXd& p) const {
  Eigen::VectorXd values = friction_values0;
  for (std::size_t k = 0; k < friction_index.size(); ++k)
    if (friction_index[k] >= 0) values(friction_index[k]) = p(static_cast<Eigen::Index>(k));
  return sensitivity::with_friction_parameters(base, values);
}

double Identification::Impl::young_for(const Eigen::VectorXd& p) const {
  for (std::size_t k = 0; k < friction_index.size(); ++k)
    if (friction_index[k] < 0) return p(static_cast<Eigen::Index>(k));
  return young0;
}

const Identification::Prediction& Identification::Impl::predict(const Eigen::VectorXd& p, bool with_jacobian) {
  if (cached && cached_parameters.size() == p.size() && cached_parameters == p) {
    if (with_jacobian && cached->ok && cached->jacobian.size() == 0) {
      Prediction& out = *cached;
      out.jacobian.setZero(static_cast<Eigen::Index>(measurements.size()), p.size());
      for (ExperimentModel& e : experiments)
        if (!add_jacobian(e, p, out)) {
          out.jacobian.resize(0, 0);
          break;
        }
    }
    return *cached;
  }
  cached_parameters = p;
  cached.emplace();
  Prediction& out = *cached;
  const double rho = young_for(p) / young0;
  out.values.resize(static_cast<Eigen::Index>(measurements.size()));
  for (std::size_t k = 0; k < experiments.size(); ++k) {
    ExperimentModel& e = experiments[k];
    e.solved = false;
    contact::FrictionLaw law = e.law0;
    try {
      law = law_for(e.law0, p);
    } catch (const InvalidInput& error) {
      out.message = error.what();  // e.g. a non-convex polygon: Ceres shrinks its step
      return out;
    }
    const linalg::ScaledOperator M(*e.M0_op, 1.0 / rho);  // M(E) = M(E₀) E₀/E, no copy
    const Eigen::VectorXd c = e.c_traction / rho + e.c_dirichlet + e.gap_vector;
    contact::ContactState state = e.warm_start ? *e.warm_start : contact::ContactState(e.dim, e.num_nodes);
    const contact::CoulombSolver solver(M, law, coulomb);
    const contact::CoulombSolver::Summary contact = solver.solve(c, state);
    if (k == 0 || !contact.converged()) out.contact = contact;
    ++state_solves;
    if (!contact.converged()) {
      out.message = (experiments.size() > 1 ? fmt::format("experiment \"{}\": ", e.name) : std::string()) +
                    "contact solve failed: " + contact.brief_report();
      return out;
    }
    e.warm_start = state;
    e.solved = true;
    out.values.segment(e.first_row, e.num_rows) = e.Lz * state.z + e.Lg * state.gradient;
    e.index_sets = sensitivity::classify(state, law).summary();
    e.num_slipping_nodes = 0;
    for (Eigen::Index i = 0; i < e.num_nodes; ++i) e.num_slipping_nodes += state.is_slip(i) ? 1 : 0;
    out.num_slipping_nodes += e.num_slipping_nodes;
    if (experiments.size() == 1) out.index_sets = e.index_sets;
    else out.index_sets += fmt::format("{}{}: {}", k ? "; " : "", e.name, e.index_sets);
  }
  out.ok = true;
  if (with_jacobian) {
    out.jacobian.setZero(static_cast<Eigen::Index>(measurements.size()), p.size());
    for (ExperimentModel& e : experiments)
      if (!add_jacobian(e, p, out)) {
        out.jacobian.resize(0, 0);
        break;
      }
  }
  return out;
}

bool Identification::Impl::add_jacobian(ExperimentModel& e, const Eigen::VectorXd& p, Prediction& out) {
  const contact::FrictionLaw law = law_for(e.law0, p);
  const double young = young_for(p);
  const double m_scale = young0 / young;  // M(E) = m_scale · M0
  const contact::ContactState& state = *e.warm_start;  // the state of the cached prediction
  const sensitivity::Piece piece = sensitivity::default_piece(sensitivity::classify(state, law));
  const sensitivity::PieceLinearization lin = sensitivity::linearize_piece(piece, law, state);
  const Eigen::MatrixXd rows = sensitivity::friction_parameter_rows(piece, law, state);
  const Eigen::Index n = p.size(), m = e.M0->rows();
  Eigen::MatrixXd Rz = Eigen::MatrixXd::Zero(m, n), Q = Eigen::MatrixXd::Zero(m, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const int index = friction_index[static_cast<std::size_t>(k)];
    if (index >= 0) Rz.col(k) = rows.col(index);
    else Q.col(k) = (state.gradient - e.gap_vector - e.c_dirichlet) / young;  // G A⁻¹ (A u − l_lift)/E
  }
  const sensitivity::ContactStateDerivative d = sensitivity::contact_state_derivative(lin, *e.M0, Rz, Q, m_scale);
  ++jacobian_evaluations;
  if (d.status != Status::kConverged) {
    out.ok = false;
    out.message = (experiments.size() > 1 ? fmt::format("experiment \"{}\": ", e.name) : std::string()) +
                  "forward sensitivity failed: " + d.message;
    return false;
  }
  out.jacobian.middleRows(e.first_row, e.num_rows) = e.Lz * d.forces + e.Lg * d.gradient;
  return true;
}

namespace {

// The case's loads scaled by one experiment's factors (as a load case scales them,
// study/load_case_definition.hpp) and its law turned by the experiment's angle.
BodyDefinition experiment_body(const BodyDefinition& body, const IdentificationExperiment& x, std::size_t k) {
  const std::string field = fmt::format("experiment[{}] (\"{}\")", k, x.name);
  const auto check = [&](const std::vector<double>& scales, std::size_t count, std::string_view key,
                         std::string_view table) {
    if (scales.empty()) return;
    if (scales.size() != count && !(scales.size() == 1 && count >= 1))
      throw InvalidInput(fmt::format("{}.{}: {} scale(s); expected one for every [[{}]] table or one per table (the "
                                     "case has {})",
                                     field, key, scales.size(), table, count));
    for (std::size_t j = 0; j < scales.size(); ++j)
      if (!std::isfinite(scales[j]))
        throw InvalidInput(fmt::format("{}.{}[{}] = {}; expected a finite number", field, key, j, scales[j]));
  };
  check(x.load_scale, body.tractions.size(), "load_scale", "load");
  check(x.dirichlet_scale, body.dirichlet.size(), "dirichlet_scale", "dirichlet");
  check(x.force_scale, body.forces.size(), "force_scale", "force");
  if (!std::isfinite(x.orientation))
    throw InvalidInput(fmt::format("{}.orientation = {}; expected a finite angle", field, x.orientation));
  BodyDefinition out = body;
  const auto at = [](const std::vector<double>& scales, std::size_t j) {
    return scales.empty() ? 1.0 : scales[scales.size() == 1 ? 0 : j];
  };
  for (std::size_t j = 0; j < out.tractions.size(); ++j) out.tractions[j].traction *= at(x.load_scale, j);
  for (std::size_t j = 0; j < out.dirichlet.size(); ++j)
    if (out.dirichlet[j].displacement.size() > 0) out.dirichlet[j].displacement *= at(x.dirichlet_scale, j);
  for (std::size_t j = 0; j < out.forces.size(); ++j) out.forces[j].force *= at(x.force_scale, j);
  if (x.orientation != 0.0) {
    if (out.contact->law.dim() == 2)
      throw InvalidInput(fmt::format("{}.orientation = {} rad; expected 0 for a 2D case (a contact line has no "
                                     "in-plane rotation)",
                                     field, x.orientation));
    out.contact->law = out.contact->law.rotated(x.orientation);
  }
  return out;
}

}  // namespace

Identification::Identification(BodyDefinition definition, std::vector<Measurement> measurements, Options options)
    : Identification(std::move(definition), std::vector<IdentificationExperiment>{[&] {
                       IdentificationExperiment x;
                       x.name = "case";
                       x.measurements = std::move(measurements);
                       return x;
                     }()},
                     std::move(options)) {}

Identification::Identification(BodyDefinition definition, std::vector<IdentificationExperiment> experiments,
                               Options options)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  Impl& s = *impl_;
  if (!definition.contact) throw InvalidInput("identification needs a body in contact: add a [contact] table to the case");
  if (definition.engine.kind != StateEngine::kDirect)
    throw InvalidInput(
        "[solver] engine = \"petsc\": identification needs the direct engine (its trial points are contact "
        "solves on the dense Delassus matrix M = G A⁻¹ Gᵀ, and its Jacobians differentiate them); expected "
        "engine = \"direct\" (docs/identification.md)");
  if (experiments.empty()) throw InvalidInput("identification: no experiment; expected at least one");
  if (experiments.size() > kMaxIdentificationExperiments)
    throw InvalidInput(fmt::format("identification: {} experiments; expected at most {} (docs/case-format.md, \"Size "
                                   "limits\")",
                                   experiments.size(), kMaxIdentificationExperiments));
  std::size_t rows = 0, totals = 0;
  for (std::size_t k = 0; k < experiments.size(); ++k) {
    const IdentificationExperiment& x = experiments[k];
    if (x.name.empty()) throw InvalidInput(fmt::format("experiment[{}].name = \"\"; expected a non-empty name", k));
    for (std::size_t j = 0; j < k; ++j)
      if (experiments[j].name == x.name)
        throw InvalidInput(fmt::format("experiment[{}].name = \"{}\" is the name of experiment[{}]; expected unique names",
                                       k, x.name, j));
    if (x.measurements.empty())
      throw InvalidInput(experiments.size() == 1
                             ? std::string("identification: no measurements; expected at least one")
                             : fmt::format("experiment[{}] (\"{}\"): no measurements; expected at least one", k, x.name));
    rows += x.measurements.size();
    totals += static_cast<std::size_t>(std::count_if(x.measurements.begin(), x.measurements.end(),
                                                     [](const Measurement& row) { return is_total(row.quantity); }));
  }
  if (rows > kMaxMeasurements)
    throw InvalidInput(fmt::format("identification: {} measurements; expected at most {} (docs/case-format.md, "
                                   "\"Size limits\")",
                                   rows, kMaxMeasurements));
  if (totals > kMaxTotalMeasurements)
    throw InvalidInput(fmt::format("identification: {} measurements of sums over the contact surface (total_*); "
                                   "expected at most {} (docs/case-format.md, \"Size limits\")",
                                   totals, kMaxTotalMeasurements));
  // The Jacobian is exact only for a state far more accurate than Ceres' steps.
  auto& co = definition.contact->coulomb;
  tighten_for_derivatives(co, options.state_tolerance);
  s.coulomb = co;
  // The Jacobians need the dense M: let the state solve form it whatever the contact size.
  definition.contact->dense_delassus_max_unknowns = std::numeric_limits<int>::max();
  s.definition = std::move(definition);
  s.options = std::move(options);
  s.setup_parameters();
  for (std::size_t k = 0; k < experiments.size(); ++k) {
    IdentificationExperiment& x = experiments[k];
    ExperimentModel e;
    e.name = x.name;
    e.orientation = x.orientation;
    e.definition = experiment_body(s.definition, x, k);
    e.law0 = e.definition.contact->law;
    e.first_row = static_cast<Eigen::Index>(s.measurements.size());
    e.num_rows = static_cast<Eigen::Index>(x.measurements.size());
    for (Measurement& m : x.measurements) {
      s.measurements.push_back(std::move(m));
      s.measurement_experiment.push_back(static_cast<int>(k));
    }
    s.experiment_names.push_back(x.name);
    s.experiments.push_back(std::move(e));
  }
  for (ExperimentModel& e : s.experiments) {
    e.body = std::make_unique<ElasticBody>(e.definition);
    if (e.body->contact_boundary()->num_unknowns() > kMaxIdentificationContactUnknowns)
      throw InvalidInput(fmt::format(
          "identification: the contact surface has {} contact unknowns (dim × {} nodes), whose dense Delassus matrix "
          "needs {:.3g} GB; expected at most {} contact unknowns (a coarser mesh on the contact surface; "
          "docs/case-format.md, \"Size limits\")",
          e.body->contact_boundary()->num_unknowns(), e.body->contact_boundary()->num_nodes(),
          8e-9 * std::pow(static_cast<double>(e.body->contact_boundary()->num_unknowns()), 2.0),
          kMaxIdentificationContactUnknowns));
    s.setup_contact(e);
    s.resolve_measurements(e);
  }
}

Identification::~Identification() = default;

const std::vector<std::string>& Identification::parameter_names() const { return impl_->names; }
Eigen::VectorXd Identification::initial_parameters() const { return impl_->initial; }
Eigen::VectorXd Identification::case_parameters() const {
  Eigen::VectorXd p(static_cast<Eigen::Index>(impl_->names.size()));
  for (std::size_t k = 0; k < impl_->names.size(); ++k) {
    const int index = impl_->friction_index[k];
    p(static_cast<Eigen::Index>(k)) = index >= 0 ? impl_->friction_values0(index) : impl_->young0;
  }
  return p;
}
const Eigen::MatrixXd& Identification::contact_coordinates() const {
  return impl_->experiments.front().body->contact_boundary()->plane_coordinates();
}
const std::vector<Measurement>& Identification::measurements() const { return impl_->measurements; }
const std::vector<std::string>& Identification::experiment_names() const { return impl_->experiment_names; }
const std::vector<int>& Identification::measurement_experiment() const { return impl_->measurement_experiment; }

Identification::Prediction Identification::predict(const Eigen::Ref<const Eigen::VectorXd>& parameters, bool with_jacobian) {
  if (parameters.size() != static_cast<Eigen::Index>(impl_->names.size()))
    throw InvalidInput(fmt::format("Identification::predict: {} parameter values; expected {}", parameters.size(),
                                   impl_->names.size()));
  return impl_->predict(parameters, with_jacobian);
}

// ------------------------------------------------------------------------------------------
// Ceres: one residual block per measurement (so a robust loss acts on each normalized residual),
// one size-1 parameter block per parameter (so bounds, constant blocks and covariance blocks are
// per parameter); all blocks share the model's cache, so a trial point costs one state solve.

namespace {
class MeasurementResidual final : public ceres::CostFunction {
 public:
  MeasurementResidual(Identification::Impl& model, std::size_t row) : model_(model), row_(row) {
    set_num_residuals(1);
    for (std::size_t k = 0; k < model.names.size(); ++k) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Index n = model_.scale.size();
    Eigen::VectorXd p(n);
    for (Eigen::Index k = 0; k < n; ++k) p(k) = parameters[k][0] * model_.scale(k);
    const Identification::Prediction& pr = model_.predict(p, jacobians != nullptr);
    if (!pr.ok) return false;
    const Measurement& m = model_.measurements[row_];
    const auto r = static_cast<Eigen::Index>(row_);
    residuals[0] = (pr.values(r) - m.value) / m.sigma;
    if (jacobians)
      for (Eigen::Index k = 0; k < n; ++k)
        if (jacobians[k]) jacobians[k][0] = pr.jacobian(r, k) * model_.scale(k) / m.sigma;
    return true;
  }

 private:
  Identification::Impl& model_;
  std::size_t row_;
};

Status status_of(ceres::TerminationType t) {
  switch (t) {
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS: return Status::kConverged;
    case ceres::NO_CONVERGENCE: return Status::kMaxIterations;
    case ceres::USER_FAILURE: return Status::kStoppedByCallback;
    case ceres::FAILURE: return Status::kNumericalFailure;
  }
  return Status::kNumericalFailure;
}
}  // namespace

namespace {

// The fit's Ceres problem: x holds the parameters divided by their scales, one size-1 block per
// parameter (bounds, constant blocks and covariance blocks per parameter), one residual block per
// measurement with the shared robust loss.
struct LeastSquaresFit {
  std::vector<double> x;
  std::vector<double*> blocks;
  std::unique_ptr<ceres::LossFunction> loss;
  std::unique_ptr<ceres::Problem> problem;
};

std::unique_ptr<LeastSquaresFit> least_squares_fit(Identification::Impl& s) {
  auto fit = std::make_unique<LeastSquaresFit>();
  const Eigen::Index n = s.scale.size();
  fit->x.resize(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) fit->x[static_cast<std::size_t>(k)] = s.initial(k) / s.scale(k);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // one loss shared by all blocks
  fit->problem = std::make_unique<ceres::Problem>(problem_options);
  if (s.options.loss == RobustLoss::kHuber) fit->loss = std::make_unique<ceres::HuberLoss>(s.options.loss_scale);
  if (s.options.loss == RobustLoss::kCauchy) fit->loss = std::make_unique<ceres::CauchyLoss>(s.options.loss_scale);
  for (double& v : fit->x) fit->blocks.push_back(&v);
  for (std::size_t r = 0; r < s.measurements.size(); ++r)
    fit->problem->AddResidualBlock(new MeasurementResidual(s, r), fit->loss.get(), fit->blocks);
  for (Eigen::Index k = 0; k < n; ++k) {
    const ParameterSpec& spec = s.options.parameters[static_cast<std::size_t>(k)];
    double* b = fit->blocks[static_cast<std::size_t>(k)];
    fit->problem->SetParameterLowerBound(b, 0, spec.lower / s.scale(k));
    fit->problem->SetParameterUpperBound(b, 0, spec.upper / s.scale(k));
  }
  return fit;
}

// Levenberg–Marquardt with dense QR, serial (the model and its cache are not thread-safe) and
// silent (the library never prints); the summary's solver fields.
void solve_fit(const Identification::Options& options, LeastSquaresFit& fit, Identification::Summary& out) {
  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, fit.problem.get(), &ceres_summary);
  out.ceres_brief_report = ceres_summary.BriefReport();
  out.ceres_full_report = ceres_summary.FullReport();
  out.iterations = std::max(0, static_cast<int>(ceres_summary.iterations.size()) - 1);  // none when it failed at once
  out.initial_cost = ceres_summary.initial_cost;
  out.final_cost = ceres_summary.final_cost;
  out.status = status_of(ceres_summary.termination_type);
  out.message = ceres_summary.message;
}

// The normalized residuals at the estimate, the χ² and each experiment's share.
void record_residuals(const Identification::Impl& s, const Identification::Prediction& final_prediction,
                      const Eigen::VectorXd& sigma, Identification::Summary& out) {
  const auto nm = static_cast<Eigen::Index>(s.measurements.size());
  Eigen::VectorXd value(nm);
  for (Eigen::Index r = 0; r < nm; ++r) value(r) = s.measurements[static_cast<std::size_t>(r)].value;
  out.predictions = final_prediction.values;
  out.residuals = (out.predictions - value).cwiseQuotient(sigma);
  out.chi_square = out.residuals.squaredNorm();
  out.index_sets = final_prediction.index_sets;
  for (const auto& e : s.experiments) {
    Identification::Summary::ExperimentResidual& r = out.experiments.emplace_back();
    r.name = e.name;
    r.first_measurement = e.first_row;
    r.num_measurements = e.num_rows;
    r.chi_square = out.residuals.segment(e.first_row, e.num_rows).squaredNorm();
    r.rms_residual = std::sqrt(r.chi_square / static_cast<double>(e.num_rows));
    r.num_slipping_nodes = e.num_slipping_nodes;
    r.index_sets = e.index_sets;
  }
}

// The measurement whose normalized residual or Jacobian row is not finite (a σ too small for its
// value, σ = 1e-308, overflows them: Eigen's and Ceres' SVDs crash on such numbers), as the
// summary's failure; false when every row is finite.
bool refuse_non_finite_rows(const Identification::Impl& s, const Eigen::MatrixXd& Js, Identification::Summary& out) {
  for (Eigen::Index r = 0; r < Js.rows(); ++r) {
    if (std::isfinite(out.residuals(r)) && Js.row(r).allFinite()) continue;
    const Measurement& m = s.measurements[static_cast<std::size_t>(r)];
    out.status = Status::kNumericalFailure;
    out.message = fmt::format(
        "{}: the normalized residual (fitted − measured)/σ = ({:g} − {:g})/{:g} = {:g} or its derivative is not a "
        "finite number; expected a standard deviation σ that the value's scale does not overflow",
        m.label.empty() ? fmt::format("measurement {}", r) : m.label, out.predictions(r), m.value, m.sigma,
        out.residuals(r));
    return true;
  }
  return false;
}

// Parameters whose column of the scaled Jacobian vanishes are not determined; a friction
// coefficient of an all-sticking state has a lower bound only, which the note gives. Returns the
// others (the "live" parameters).
std::vector<Eigen::Index> mark_undetermined(const Identification::Impl& s, const Eigen::MatrixXd& Js,
                                            const Eigen::VectorXd& p, int num_slipping_nodes,
                                            Identification::Summary& out) {
  const Eigen::VectorXd column_norms = Js.colwise().norm();
  std::vector<Eigen::Index> live;
  for (Eigen::Index k = 0; k < Js.cols(); ++k) {
    Identification::ParameterEstimate& e = out.estimates[static_cast<std::size_t>(k)];
    if (column_norms(k) > s.options.zero_column_tolerance) {
      live.push_back(k);
      continue;
    }
    e.identifiability = Identifiability::kNotDetermined;
    const bool friction = s.friction_index[static_cast<std::size_t>(k)] >= 0;
    if (!friction || num_slipping_nodes > 0) {
      e.note = friction ? "no measured quantity depends on it: no slipping node uses this coefficient at the "
                          "estimate (its Jacobian column is zero)"
                        : "no measured quantity depends on it (its Jacobian column is zero)";
      continue;
    }
    // Every node sticks (or separates): any coefficient above the one that puts the most loaded
    // friction force on the boundary of λW gives the same state. Over every experiment, each
    // with its own (turned) law.
    double g = 0.0;
    for (const auto& model : s.experiments) {
      const contact::FrictionLaw law = s.law_for(model.law0, p);
      const contact::ContactState& state = *model.warm_start;  // the final prediction's state
      for (Eigen::Index i = 0; i < model.num_nodes; ++i) {
        const double lambda = state.lambda(i);
        if (lambda > 0) g = std::max(g, law.gauge(state.q(i) / lambda));
      }
    }
    e.note = s.friction_values0.size() == 1
                 ? fmt::format("only a lower bound: {} >= {:.6g} (every contact node sticks, so any larger "
                               "coefficient explains the data equally well)",
                               e.name, g * p(k))
                 : fmt::format("only bounded from below: every contact node sticks (the friction forces lie "
                               "inside λ·W, scaling W by {:.4g} would still hold them), so the data cannot "
                               "determine the coefficients",
                               g);
  }
  return live;
}

// Of the live parameters, those with a visible share (> 1e-3) in a null direction of the scaled
// Jacobian's live columns are determined only in combination (marked correlated); returns the
// determined rest. Records the singular values.
std::vector<Eigen::Index> mark_correlated(const Identification::Options& options, const Eigen::MatrixXd& Js,
                                          const std::vector<Eigen::Index>& live, Identification::Summary& out) {
  const auto nl = static_cast<Eigen::Index>(live.size());
  Eigen::MatrixXd Jl(Js.rows(), nl);
  for (Eigen::Index j = 0; j < nl; ++j) Jl.col(j) = Js.col(live[static_cast<std::size_t>(j)]);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jl, Eigen::ComputeFullV);
  out.singular_values = svd.singularValues();
  const Eigen::VectorXd& sv = svd.singularValues();
  std::vector<Eigen::Index> correlated;
  if (sv.size() < nl || sv(sv.size() - 1) <= options.rank_tolerance * sv(0)) {
    for (Eigen::Index j = 0; j < nl; ++j) {
      double share = 0.0;
      for (Eigen::Index c = 0; c < nl; ++c)
        if (c >= sv.size() || sv(c) <= options.rank_tolerance * sv(0))
          share = std::max(share, std::abs(svd.matrixV()(j, c)));
      if (share > 1e-3) correlated.push_back(live[static_cast<std::size_t>(j)]);
    }
    for (Eigen::Index k : correlated) {
      Identification::ParameterEstimate& e = out.estimates[static_cast<std::size_t>(k)];
      e.identifiability = Identifiability::kCorrelated;
      e.note = "only a combination with other parameters is determined (the Jacobian is rank deficient)";
    }
  }
  std::vector<Eigen::Index> determined;
  for (Eigen::Index k : live)
    if (std::find(correlated.begin(), correlated.end(), k) == correlated.end()) determined.push_back(k);
  return determined;
}

// Covariance of the determined parameters with the others held fixed (Ceres, dense SVD), their
// standard deviations and correlations; a parameter on a bound is marked so.
void record_covariance(const Identification::Impl& s, LeastSquaresFit& fit, const std::vector<Eigen::Index>& determined,
                       Identification::Summary& out) {
  const Eigen::Index n = s.scale.size();
  for (Eigen::Index k = 0; k < n; ++k)
    if (std::find(determined.begin(), determined.end(), k) == determined.end())
      fit.problem->SetParameterBlockConstant(fit.blocks[static_cast<std::size_t>(k)]);
  if (determined.empty()) return;
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  co.num_threads = 1;
  co.null_space_rank = 0;  // rank deficiency was handled before: fail rather than drop directions
  co.min_reciprocal_condition_number = s.options.rank_tolerance * s.options.rank_tolerance;
  ceres::Covariance covariance(co);
  const auto block = [&](Eigen::Index k) { return fit.blocks[static_cast<std::size_t>(k)]; };
  std::vector<std::pair<const double*, const double*>> pairs;
  for (Eigen::Index a : determined)
    for (Eigen::Index b : determined)
      if (a <= b) pairs.emplace_back(block(a), block(b));
  if (!covariance.Compute(pairs, fit.problem.get())) {
    for (Eigen::Index k : determined) {
      Identification::ParameterEstimate& e = out.estimates[static_cast<std::size_t>(k)];
      e.identifiability = Identifiability::kCorrelated;
      e.note = "ceres::Covariance found the Jacobian rank deficient";
    }
    return;
  }
  for (Eigen::Index a : determined)
    for (Eigen::Index b : determined) {
      if (a > b) continue;
      double v = kNaN;
      (void)covariance.GetCovarianceBlock(block(a), block(b), &v);
      out.covariance(a, b) = out.covariance(b, a) = v * s.scale(a) * s.scale(b);
    }
  for (Eigen::Index k : determined) {
    Identification::ParameterEstimate& e = out.estimates[static_cast<std::size_t>(k)];
    e.standard_deviation = std::sqrt(out.covariance(k, k));
    const double tol = 1e-9 * s.scale(k);
    const bool at_bound = std::abs(e.value - e.lower) <= tol || std::abs(e.value - e.upper) <= tol;
    e.identifiability = at_bound ? Identifiability::kAtBound : Identifiability::kDetermined;
    if (at_bound) e.note = "the estimate is on a bound: the deviation is that of the unconstrained problem";
  }
  for (Eigen::Index a : determined)
    for (Eigen::Index b : determined)
      out.correlation(a, b) = out.covariance(a, b) / std::sqrt(out.covariance(a, a) * out.covariance(b, b));
}

}  // namespace

Identification::Summary Identification::run() {
  const auto start = std::chrono::steady_clock::now();
  Impl& s = *impl_;
  Summary out;
  const Eigen::Index n = s.scale.size();
  const auto nm = static_cast<Eigen::Index>(s.measurements.size());
  const int solves_before = s.state_solves, jacobians_before = s.jacobian_evaluations;
  const auto finish = [&] {
    out.state_solves = s.state_solves - solves_before;
    out.jacobian_evaluations = s.jacobian_evaluations - jacobians_before;
    out.time_seconds = seconds_since(start);
    return out;
  };
  const std::unique_ptr<LeastSquaresFit> fit = least_squares_fit(s);
  solve_fit(s.options, *fit, out);
  out.degrees_of_freedom = static_cast<int>(nm - n);

  Eigen::VectorXd p(n);
  for (Eigen::Index k = 0; k < n; ++k) p(k) = fit->x[static_cast<std::size_t>(k)] * s.scale(k);
  const Prediction final_prediction = s.predict(p, true);
  out.estimates.resize(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    const ParameterSpec& spec = s.options.parameters[static_cast<std::size_t>(k)];
    Identification::ParameterEstimate& e = out.estimates[static_cast<std::size_t>(k)];
    e.name = spec.name;
    e.initial = s.initial(k);
    e.value = p(k);
    e.lower = spec.lower;
    e.upper = spec.upper;
  }
  out.covariance = Eigen::MatrixXd::Constant(n, n, kNaN);
  out.correlation = Eigen::MatrixXd::Constant(n, n, kNaN);
  if (!final_prediction.ok) {
    out.status = Status::kNumericalFailure;
    out.message = "the model could not be evaluated at the estimate: " + final_prediction.message;
    out.time_seconds = seconds_since(start);
    return out;
  }
  Eigen::VectorXd sigma(nm);
  for (Eigen::Index r = 0; r < nm; ++r) sigma(r) = s.measurements[static_cast<std::size_t>(r)].sigma;
  record_residuals(s, final_prediction, sigma, out);

  // Identifiability on the scaled Jacobian J_s = diag(1/σ) J diag(scale): column k is the change
  // of the normalized residuals for a 100% change of parameter k.
  const Eigen::MatrixXd Js = sigma.cwiseInverse().asDiagonal() * final_prediction.jacobian * s.scale.asDiagonal();
  if (refuse_non_finite_rows(s, Js, out)) return finish();
  const std::vector<Eigen::Index> live = mark_undetermined(s, Js, p, final_prediction.num_slipping_nodes, out);
  if (!live.empty()) record_covariance(s, *fit, mark_correlated(s.options, Js, live, out), out);
  return finish();
}

std::vector<Measurement> synthetic_measurements(const std::vector<Measurement>& templates,
                                                const Eigen::Ref<const Eigen::VectorXd>& exact, std::uint64_t seed,
                                                bool add_noise) {
  if (exact.size() != static_cast<Eigen::Index>(templates.size()))
    throw InvalidInput(fmt::format("synthetic_measurements: {} exact values for {} templates", exact.size(), templates.size()));
  std::mt19937_64 rng{seed};
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Measurement> out = templates;
  for (std::size_t r = 0; r < out.size(); ++r) {
    out[r].value = exact(static_cast<Eigen::Index>(r));
    if (add_noise) out[r].value += out[r].sigma * normal(rng);
  }
  return out;
}

std::vector<IdentificationExperiment> synthetic_experiments(std::vector<IdentificationExperiment> experiments,
                                                            const Eigen::Ref<const Eigen::VectorXd>& exact,
                                                            std::uint64_t seed, bool add_noise) {
  std::vector<Measurement> rows;
  for (const auto& x : experiments) rows.insert(rows.end(), x.measurements.begin(), x.measurements.end());
  const std::vector<Measurement> synthetic = synthetic_measurements(rows, exact, seed, add_noise);
  auto next = synthetic.begin();
  for (auto& x : experiments)
    for (Measurement& m : x.measurements) m = *next++;
  return experiments;
}

}  // namespace frictopt::study
