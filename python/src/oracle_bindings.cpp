// SPDX-License-Identifier: MIT
// frictopt.Oracle (study::ShapeOracle: Θ(α) and a Clarke subgradient ξ by one adjoint solve),
// frictopt.check_gradient (ξ against central differences, as `frictopt check-gradient`) and
// frictopt.certify (study::certify, the fields of `frictopt certify`'s certificate.json).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/study/derivative_accuracy.hpp"
#include "frictopt/study/gradient_check.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/certificate.hpp"

namespace frictopt::python {

namespace {

std::shared_ptr<Oracle> make_oracle(std::shared_ptr<const Case> source, const study::BodyDefinition& definition) {
  auto o = std::make_shared<Oracle>();
  o->source = source;
  if (!definition.contact) throw InvalidInput(source->description.origin + ": the oracle needs a [contact] table");
  const study::CostDefinition& cost = source->description.required_cost();
  py::gil_scoped_release release;
  o->body = std::make_unique<study::ElasticBody>(definition);
  o->oracle = std::make_unique<study::ShapeOracle>(*o->body, cost);
  return o;
}

// x⁰: α⁰, or (α⁰, s⁰) with friction_orientation (the body turns its law per design).
Eigen::VectorXd initial_design(const Oracle& o) { return o.body->initial_design(); }

}  // namespace

void bind_oracle(py::module_& m) {
  py::class_<study::Evaluation>(m, "Evaluation", R"doc(
One evaluation of the oracle at a design: Θ(α) [units of the cost, e.g. N² for target_pressure]
and one Clarke subgradient ξ ∈ ∂Θ(α) [cost units per m] from one adjoint solve, with the
index sets that tell whether Θ is differentiable there (no weak nodes). ``ok`` is False, with
a ``message``, when the state or the adjoint failed (numerical failure is not an exception).
)doc")
      .def_readonly("ok", &study::Evaluation::ok, "False when the state solve or the adjoint failed.")
      .def_readonly("message", &study::Evaluation::message, "Why not ok.")
      .def_readonly("value", &study::Evaluation::value, "Θ(α) in the cost's units.")
      .def_property_readonly("subgradient", [](const study::Evaluation& e) { return to_numpy(e.subgradient); },
                             "ξ for the default piece, (d,) [cost units per m]; empty when not requested.")
      .def_property_readonly("friction_gradient", [](const study::Evaluation& e) { return to_numpy(e.friction_gradient); },
                             "∂Θ/∂p for the friction parameters p of the law (Oracle.friction_parameters).")
      .def_property_readonly("index_sets", [](const study::Evaluation& e) { return e.index_sets.summary(); },
                             "The contact index sets at α, one line.")
      .def_property_readonly("weak_nodes", [](const study::Evaluation& e) { return e.index_sets.num_weak_nodes(); },
                             "Nodes on a kink (weak contact / stick-slip transition): Θ need not be differentiable.")
      .def_property_readonly("contact_report", [](const study::Evaluation& e) { return e.contact.brief_report(); },
                             "The contact solver's one-line report.")
      .def_property_readonly("adjoint_report", [](const study::Evaluation& e) { return e.adjoint.brief_report(); },
                             "The adjoint solve's one-line report.")
      .def_readonly("state_seconds", &study::Evaluation::state_seconds, "Wall time of the state solve [s].")
      .def_readonly("subgradient_seconds", &study::Evaluation::subgradient_seconds, "Wall time of the adjoint [s].")
      .def("__repr__", [](const study::Evaluation& e) {
        return e.ok ? fmt::format("<frictopt.Evaluation Θ = {:.10g}, |ξ| = {:.4g}, {}>", e.value,
                                  e.subgradient.size() ? e.subgradient.norm() : kNaN, e.index_sets.summary())
                    : "<frictopt.Evaluation failed: " + e.message + ">";
      });

  py::class_<Oracle, std::shared_ptr<Oracle>>(m, "Oracle", R"doc(
The shape problem as an oracle: Θ(α) = J(α, S(α)) — the case's [cost] of the contact state
S(α) — and one Clarke subgradient ξ by one adjoint solve (docs/sensitivity.md). Results are
cached per design. The oracle owns its body (a separate study::ElasticBody), so Body.solve
elsewhere cannot disturb it. Evaluations release the GIL.

Example::

    oracle = frictopt.Oracle(case)
    e = oracle.evaluate(case.initial_design)     # Evaluation: e.value, e.subgradient
    theta, xi = oracle(alpha)
)doc")
      .def(py::init([](std::shared_ptr<const Case> source) { return make_oracle(source, source->description.body); }),
           py::arg("case"), "Builds the body and the cost; ValueError without [contact] or [cost].")
      .def(
          "evaluate",
          [](Oracle& o, const py::object& alpha, bool with_subgradient) {
            const Eigen::VectorXd a = design_from_python(alpha, initial_design(o), "alpha");
            if (!alpha.is_none()) warn_if_outside(*o.body, a, "alpha");
            py::gil_scoped_release release;
            const std::lock_guard lock(o.mutex);
            return study::Evaluation(o.oracle->evaluate_design(a, with_subgradient));
          },
          py::arg("alpha") = py::none(), py::arg("with_subgradient") = true,
          "Θ(α) and (if requested) ξ at the design α [m] (default α⁰). Raises ValueError for a wrong size or\n"
          "an inverting design; a failed solve gives ok = False.")
      .def(
          "__call__",
          [](Oracle& o, const py::object& alpha) {
            const Eigen::VectorXd a = design_from_python(alpha, initial_design(o), "alpha");
            if (!alpha.is_none()) warn_if_outside(*o.body, a, "alpha");
            study::Evaluation e;
            {
              py::gil_scoped_release release;
              const std::lock_guard lock(o.mutex);
              e = o.oracle->evaluate_design(a, true);
            }
            if (!e.ok) return py::make_tuple(kNaN, to_numpy(Eigen::VectorXd(Eigen::VectorXd::Constant(a.size(), kNaN))));
            return py::make_tuple(e.value, to_numpy(e.subgradient));
          },
          py::arg("alpha"), "(Θ(α), ξ) as (float, numpy array); NaNs when the evaluation failed.")
      .def_property_readonly("cost", [](const Oracle& o) { return o.oracle->cost().name(); }, "The cost's name.")
      .def_property_readonly("num_design_variables", [](const Oracle& o) { return initial_design(o).size(); },
                             "d, the number of design variables.")
      .def_property_readonly("initial_design", [](const Oracle& o) { return to_numpy(initial_design(o)); }, "x⁰: α⁰ [m] (and s⁰ = kφ⁰ last with [design] friction_orientation).")
      .def_property_readonly("num_state_solves", [](const Oracle& o) { return o.oracle->num_state_solves(); },
                             "State problems solved so far (cache hits do not count).")
      .def_property_readonly(
          "friction_parameters",
          [](const Oracle& o) { return sensitivity::friction_parameters(o.body->definition().contact->law).names; },
          "Names of the friction parameters of Evaluation.friction_gradient (e.g. 'mu_vertices[0]').")
      .def("__repr__", [](const Oracle& o) {
        return fmt::format("<frictopt.Oracle cost {} on '{}', {} design variables, {} state solves>",
                           o.oracle->cost().name(), o.body->definition().name, initial_design(o).size(),
                           o.oracle->num_state_solves());
      });

  m.def(
      "check_gradient",
      [](std::shared_ptr<const Case> source, const py::object& design, double relative_step) {
        // As `frictopt check-gradient`: tighter solver tolerances so that differences resolve ξ.
        study::BodyDefinition definition = source->description.body;
        if (!definition.contact) throw InvalidInput(source->description.origin + ": check_gradient needs a [contact] table");
        study::tighten_for_derivatives(definition.contact->coulomb);
        if (!(relative_step > 0.0)) throw InvalidInput(fmt::format("relative_step = {}; expected > 0", relative_step));
        auto o = make_oracle(source, definition);
        const Eigen::VectorXd alpha = design_from_python(design, o->body->initial_design(), "design");
        // The same admissibility check as certify: Θ and ξ are defined on Υ only.
        study::require_admissible_design(*o->body, alpha, study::CertifyOptions{}.active_tolerance,
                                         source->description.origin + (design.is_none() ? ": design.initial" : ": design"));
        io::JsonValue json = io::JsonValue::object();
        json["command"] = "check-gradient";
        json["case"] = source->description.origin;
        json["cost"] = o->oracle->cost().name();
        {
          py::gil_scoped_release release;
          // The one check of `frictopt check-gradient` (study::check_gradient): steps relative to
          // the bounds' widths, one-sided quotients, the nodes that change piece, the verdicts.
          const study::GradientCheck check = study::check_gradient(*o->oracle, alpha, relative_step);
          const study::Evaluation& e = check.evaluation;
          json["ok"] = e.ok;
          json["message"] = e.message;
          json["alpha"] = alpha;
          json["value"] = e.value;
          json["contact"] = e.contact.brief_report();
          json["adjoint"] = e.adjoint.brief_report();
          if (e.ok) {
            json["index_sets"] = e.index_sets.summary();
            json["weak_nodes"] = e.index_sets.num_weak_nodes();
            json["cardinality_L"] = check.cardinality;
            const auto n = static_cast<Eigen::Index>(check.components.size());
            Eigen::VectorXd fd(n), forward(n), backward(n), error(n), steps(n);
            io::JsonValue verdicts = io::JsonValue::array(), changes = io::JsonValue::array();
            for (Eigen::Index k = 0; k < n; ++k) {
              const auto& c = check.components[static_cast<std::size_t>(k)];
              fd(k) = c.finite_difference;
              forward(k) = c.forward_difference;
              backward(k) = c.backward_difference;
              error(k) = c.relative_error;  // relative to max|ξ|
              steps(k) = c.step;
              verdicts.push_back(std::string(study::to_string(c.verdict)));
              io::JsonValue nodes = io::JsonValue::array();
              for (const auto& p : c.piece_changes) {
                io::JsonValue change = io::JsonValue::object();
                change["node"] = p.node;
                change["side"] = p.side;
                change["step"] = p.step;
                change["before"] = p.before;
                change["after"] = p.after;
                nodes.push_back(change);
              }
              changes.push_back(nodes);
            }
            json["step"] = check.step;
            json["steps"] = steps;
            json["step_scale"] = check.step_scale;
            json["relative_step"] = relative_step;
            json["subgradient"] = e.subgradient;
            json["finite_difference"] = fd;
            json["forward_difference"] = forward;
            json["backward_difference"] = backward;
            json["relative_error"] = error;
            json["max_relative_error"] = check.worst_relative_error;
            json["verdicts"] = verdicts;
            json["piece_changes"] = changes;
            json["noise_relative"] = check.noise_relative;
            io::JsonValue warnings = io::JsonValue::array();
            for (const std::string& w : check.warnings) warnings.push_back(w);
            json["warnings"] = warnings;
            io::JsonValue friction = io::JsonValue::object();
            const auto params = sensitivity::friction_parameters(definition.contact->law);
            for (Eigen::Index k = 0; k < e.friction_gradient.size(); ++k)
              friction[params.names[static_cast<std::size_t>(k)]] = e.friction_gradient(k);
            json["friction_gradient"] = friction;
          }
        }
        return to_python(json);
      },
      py::arg("case"), py::arg("design") = py::none(), py::arg("relative_step") = 1e-6,
      R"doc(The adjoint subgradient ξ against central differences of Θ, per component (as the CLI's
``frictopt check-gradient``), with tightened contact tolerances. Returns a Summary: value, subgradient,
finite_difference (central), forward_difference, backward_difference, relative_error
(|fd − ξ_k| / max|ξ|), max_relative_error, steps h_k = relative_step·step_scale_k (the width of
variable k's bounds in Υ, C0 for a control height; ``step`` the largest), verdicts ("match",
"kink": a node changes piece within ±h and ξ_k is a one-sided quotient, "MISMATCH"),
piece_changes (per component the nodes whose index set differs at α ± h e_k: node, side ±1,
step, before, after), warnings (why the check may mean nothing here), index_sets, weak_nodes,
cardinality_L and friction_gradient {name: ∂Θ/∂p}. ``ok`` is False when the solve failed.)doc");

  m.def(
      "certify",
      [](const py::object& case_object, const py::object& alpha_object, const py::object& run_directory, int cap,
         double sample_radius, int samples) {
        std::shared_ptr<const Case> source;
        Eigen::VectorXd alpha;
        std::string design_name = "python";
        namespace fs = std::filesystem;
        std::optional<io::RunDirectory> run;
        if (!run_directory.is_none()) {
          run.emplace(run_directory.cast<fs::path>(), io::RunOpening::kExisting);
          source = py::module_::import("frictopt").attr("load_case")(run->store_case()).cast<std::shared_ptr<Case>>();
          const fs::path design_path = run->file(io::RunDirectory::kFinalDesign);
          alpha = io::read_design_file(design_path, case_initial_design(source->description).size());
          design_name = design_path.string();
        } else {
          if (case_object.is_none()) throw InvalidInput("certify: pass a case or a run_directory");
          source = case_object.cast<std::shared_ptr<Case>>();
          alpha = design_from_python(alpha_object, case_initial_design(source->description), "alpha");
        }
        auto o = make_oracle(source, source->description.body);
        // The run's checkpoint names its problem: an edited case.toml is not the run's.
        if (run) run->check_run_fingerprint(io::fingerprint_of(source->description, *o->body));
        study::CertifyOptions options;
        options.cap = cap;
        options.sample_radius = sample_radius;
        options.samples = samples;
        options.validate();
        study::Certificate c;
        {
          py::gil_scoped_release release;
          c = study::certify(*o->oracle, alpha, options);
        }
        // The certificate.json of `frictopt certify` (same keys).
        io::JsonValue json = io::JsonValue::object();
        json["command"] = "certify";
        io::add_members(json, io::run_environment());
        json["case"] = run ? run->file(io::RunDirectory::kCaseCopy).string() : source->description.origin;
        json["design"] = design_name;
        json["cost"] = o->oracle->cost().name();
        io::add_members(json, io::to_json(c, options));
        {
          py::gil_scoped_release release;
          io::add_members(json, io::load_comparison(*o->oracle, alpha, o->body->initial_design()));
        }
        if (run) run->write_json_file(io::RunDirectory::kCertificate, json);
        py::object result = to_python(json);
        result.attr("__setitem__")("report", c.report());
        return result;
      },
      py::arg("case") = py::none(), py::arg("alpha") = py::none(), py::kw_only(), py::arg("run_directory") = py::none(),
      py::arg("cap") = 4096, py::arg("sample_radius") = 0.0, py::arg("samples") = 0,
      R"doc(The optimality certificate of a design (thesis §5.3; docs/certificate.md): index sets, |𝕃| and
the ξ_i of its pieces, the Clarke stationarity distance δ = dist(0, conv{ξ_i} + N_Υ(α)), condition
(MF1′) and the extreme-point check. Either ``certify(case, alpha)`` (α [m], default α⁰) or
``certify(run_directory=DIR)`` for a run written by ``optimize`` (reads DIR/case.toml and
DIR/final_design.json, writes DIR/certificate.json like ``frictopt certify``). Returns a Summary
with the fields of certificate.json plus ``report`` (the CLI's text). ``cap`` bounds the pieces
enumerated (above it a seeded sample). ``sample_radius`` [m] > 0 adds the sampled (Goldstein)
certificate over ξ at ``samples`` admissible designs within that radius (default 10(d + 1)),
returned as ``goldstein`` (``frictopt certify --sample-radius``). A failed solve is the status,
not an exception.)doc");
}

}  // namespace frictopt::python
