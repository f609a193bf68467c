// SPDX-License-Identifier: MIT
// frictopt.optimize: the bundle trust method on Θ over Υ (study::optimize) with a Python
// callback per outer iteration, Ctrl-C handling and an optional run directory (run_directory.hpp).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>
#include <optional>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_kind.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "run_directory.hpp"

namespace frictopt::python {

namespace {

// The progress object given to callbacks: the history.csv row (same column names) plus α.
py::object progress_to_python(const study::OptimizationProgress& p, std::int64_t solves_offset, double elapsed_offset) {
  const auto row = RunDirectory::history_row(p, solves_offset, elapsed_offset);
  const auto& columns = RunDirectory::history_columns();
  py::dict d;
  for (std::size_t k = 0; k < columns.size(); ++k)
    std::visit([&](const auto& v) { d[py::str(columns[k])] = py::cast(v); }, row[k]);
  d["alpha"] = to_numpy(p.method.x);
  d["objective_scale"] = p.method.objective_scale;
  return py::module_::import("frictopt._summary").attr("Summary")(d);
}

template <class T>
void override_option(T& field, const py::object& value) {
  if (!value.is_none()) field = value.cast<T>();
}

}  // namespace

void bind_optimize(py::module_& m) {
  m.def(
      "optimize",
      [](const py::object& case_object, const py::object& run_directory, const py::object& callback, bool resume,
         bool force, const py::object& max_iterations, const py::object& max_evaluations, const py::object& epsilon) {
        namespace fs = std::filesystem;
        // The run directory (optional) decides which case is solved: on resume its stored copy.
        std::optional<RunDirectory> run;
        std::shared_ptr<const Case> source;
        if (!run_directory.is_none()) run.emplace(run_directory.cast<fs::path>(), resume, force);
        else if (resume) throw InvalidInput("resume=True needs a run_directory");
        if (run && resume)
          source = py::module_::import("frictopt").attr("load_case")(run->case_path()).cast<std::shared_ptr<Case>>();
        else if (case_object.is_none())
          throw InvalidInput("optimize: pass a case (or a run_directory with resume=True)");
        else
          source = case_object.cast<std::shared_ptr<Case>>();
        const io::CaseDescription& description = source->description;
        const study::BodyDefinition& definition = description.body;
        if (!definition.contact) throw InvalidInput(description.origin + ": optimize needs a [contact] table");

        optim::BundleTrust::Options options = description.optimization;
        override_option(options.max_iterations, max_iterations);
        override_option(options.max_evaluations, max_evaluations);
        override_option(options.epsilon, epsilon);
        options.validate();

        std::unique_ptr<study::ElasticBody> body;
        std::unique_ptr<study::ShapeOracle> oracle;
        {
          py::gil_scoped_release release;
          body = std::make_unique<study::ElasticBody>(definition);
        }
        const std::string violation = body->admissible_set().describe_violation(definition.initial_design, 1e-9);
        if (!violation.empty())
          throw InvalidInput(
              fmt::format("{}: the initial design is outside the admissible set: {}", description.origin, violation));
        {
          py::gil_scoped_release release;
          oracle = std::make_unique<study::ShapeOracle>(*body, description.required_cost());
        }
        if (run) run->start(source->toml, definition.name, description.output.vtk, description.output.every);
        const std::int64_t solves_offset = run ? run->solves_offset() : 0;
        const double elapsed_offset = run ? run->elapsed_offset() : 0.0;

        // A Python exception (from the callback, or KeyboardInterrupt from Ctrl-C) stops the run
        // at the end of the iteration; it is raised again once the run directory is complete.
        std::optional<py::error_already_set> pending;
        const auto on_progress = [&](const study::OptimizationProgress& p) {
          if (run) run->record(p, *body, *oracle);
          py::gil_scoped_acquire acquire;
          if (PyErr_CheckSignals() != 0) {  // Ctrl-C arrived while C++ was working
            pending.emplace();
            return CallbackResult::kStop;
          }
          if (callback.is_none()) return CallbackResult::kContinue;
          try {
            const py::object result = callback(progress_to_python(p, solves_offset, elapsed_offset));
            if (result.is(py::bool_(false))) return CallbackResult::kStop;
          } catch (py::error_already_set& e) {
            if (!e.matches(PyExc_StopIteration)) pending.emplace(std::move(e));
            return CallbackResult::kStop;
          }
          return CallbackResult::kContinue;
        };

        optim::BundleTrust::Summary summary;
        study::Evaluation final;
        double initial_value = kNaN;
        {
          py::gil_scoped_release release;
          if (run && !run->resuming()) run->write_design_vtu(0, definition.initial_design, *body, *oracle);
          initial_value = oracle->evaluate_design(definition.initial_design, !resume).value;
          summary = study::optimize(*oracle, options, on_progress, run ? run->checkpoint() : nullptr);
          final = oracle->evaluate_design(summary.x, true);
        }
        // The summary.json of `frictopt optimize` (same keys).
        io::JsonValue json = io::JsonValue::object();
        json["case"] = run ? run->case_path().string() : description.origin;
        json["command"] = "optimize";
        json["cost"] = oracle->cost().name();
        json["status"] = std::string(to_string(summary.status));
        json["message"] = summary.message;
        json["stopped_by"] = summary.status == Status::kMaxIterations
                                 ? std::string(summary.evaluation_limit ? "max_evaluations" : "max_iterations")
                                 : std::string(to_string(summary.status));
        json["initial_cost"] = initial_value;
        json["final_cost"] = final.value;
        json["alpha"] = summary.x;
        json["initial_alpha"] = definition.initial_design;
        json["iterations"] = summary.iterations;
        json["serious_steps"] = summary.serious_steps;
        json["null_steps"] = summary.null_steps;
        json["evaluations"] = summary.evaluations;
        json["failed_evaluations"] = summary.failed_evaluations;
        json["stationarity"] = summary.stationarity;
        json["aggregate_error"] = summary.aggregate_error;
        json["objective_scale"] = summary.objective_scale;
        json["stationarity_relative"] = summary.stationarity / summary.objective_scale;
        json["cost_kind"] = std::string(cost::to_string(description.required_cost().kind));
        json["state_solves"] = solves_offset + oracle->num_state_solves();
        json["time_seconds"] = summary.time_seconds;
        json["elapsed_seconds"] = elapsed_offset + summary.time_seconds;
        json["final_index_sets"] = final.index_sets.summary();
        json["final_contact"] = final.contact.brief_report();
        if (run) {
          py::gil_scoped_release release;
          run->finish(summary, json, *body, *oracle);
        }
        if (pending) throw std::move(*pending);

        py::object result = to_python(json);
        // The per-iteration history of this process as numpy columns.
        py::dict history;
        const auto column = [&](auto field) {
          Eigen::VectorXd v(static_cast<Eigen::Index>(summary.history.size()));
          for (std::size_t k = 0; k < summary.history.size(); ++k) v(static_cast<Eigen::Index>(k)) = field(summary.history[k]);
          return to_numpy(v);
        };
        history["iteration"] = column([](const auto& h) { return static_cast<double>(h.iteration); });
        history["evaluations"] = column([](const auto& h) { return static_cast<double>(h.evaluations); });
        history["theta"] = column([](const auto& h) { return h.f; });
        history["t"] = column([](const auto& h) { return h.t; });
        history["stationarity_relative"] = column([](const auto& h) { return h.stationarity; });
        result.attr("__setitem__")("history", py::module_::import("frictopt._summary").attr("Summary")(history));
        result.attr("__setitem__")("run_directory", run ? py::cast(run->path()) : py::none());
        return result;
      },
      py::arg("case") = py::none(), py::arg("run_directory") = py::none(), py::kw_only(),
      py::arg("callback") = py::none(), py::arg("resume") = false, py::arg("force") = false,
      py::arg("max_iterations") = py::none(), py::arg("max_evaluations") = py::none(), py::arg("epsilon") = py::none(),
      R"doc(Minimizes the case's cost Θ(α) over the admissible designs Υ by the bundle trust method
(docs/optim.md) from α⁰, as ``frictopt optimize``.

callback(progress) is called after every outer iteration with a Summary whose fields are the
columns of history.csv (iteration, evaluations, step, theta [cost units], t,
stationarity_relative, ..., state_solves, elapsed_seconds [s]) plus alpha [m]. Returning False
or raising StopIteration stops the run cleanly (status 'stopped_by_callback'); any other
exception stops it and is re-raised after the run directory is complete. Ctrl-C
(KeyboardInterrupt) is honoured at the next iteration the same way.

run_directory: when given, writes the CLI's layout there (case.toml, history.csv,
checkpoint.json, VTK series every [output].every iterations, final_design.json, summary.json);
resume=True continues the run it holds from its checkpoint (using its case.toml; ``case`` may
be None); force=True replaces a previous run's files. max_iterations, max_evaluations and
epsilon override the case's [optimization] values.

Returns a Summary with the fields of the CLI's summary.json (status, message, stopped_by,
initial_cost, final_cost, alpha, iterations, evaluations, stationarity, ...) plus history
(numpy columns) and run_directory. Non-convergence is a status, not an exception.)doc");
}

}  // namespace frictopt::python
