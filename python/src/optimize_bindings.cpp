// SPDX-License-Identifier: MIT
// frictopt.optimize: the bundle trust method on Θ over Υ (study::optimize) with a Python
// callback per outer iteration, Ctrl-C handling and an optional run directory
// (io::RunDirectory, the CLI's layout and rules: `frictopt optimize` and this function write
// the same files, and either can resume or certify the other's runs).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>
#include <optional>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/cost/cost_kind.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace frictopt::python {

namespace {

// The columns of history.csv, as apps/frictopt/optimize_command.cpp writes them; also the
// fields of the progress object a callback receives.
const std::vector<std::string> kHistoryColumns = {
    "iteration",    "evaluations",        "step",          "theta",      "t",           "stationarity_relative",
    "aggregate_error_relative", "bundle_size", "serious_steps", "null_steps", "state_solves", "coulomb_iterations",
    "qp_iterations", "weak_nodes",        "state_seconds", "subgradient_seconds", "elapsed_seconds"};

std::vector<io::CsvValue> history_row(const study::OptimizationProgress& p, std::int64_t solves, double elapsed) {
  const auto& m = p.method;
  return {static_cast<std::int64_t>(m.iteration), static_cast<std::int64_t>(m.evaluations),
          std::string(optim::to_string(m.step)), m.f, m.t, m.stationarity, m.aggregate_error,
          static_cast<std::int64_t>(m.bundle.size()), static_cast<std::int64_t>(m.serious_steps),
          static_cast<std::int64_t>(m.null_steps), solves, static_cast<std::int64_t>(p.center.contact.iterations),
          static_cast<std::int64_t>(p.center.contact.qp_iterations),
          static_cast<std::int64_t>(p.center.index_sets.num_weak_nodes()), p.center.state_seconds,
          p.center.subgradient_seconds, elapsed};
}

// The progress object given to callbacks: the history.csv row (same names) plus α.
py::object progress_to_python(const std::vector<io::CsvValue>& row, const study::OptimizationProgress& p) {
  py::dict d;
  for (std::size_t k = 0; k < kHistoryColumns.size(); ++k)
    std::visit([&](const auto& v) { d[py::str(kHistoryColumns[k])] = py::cast(v); }, row[k]);
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
        std::optional<io::RunDirectory> run;
        if (!run_directory.is_none())
          run.emplace(run_directory.cast<fs::path>(),
                      resume ? io::RunOpening::kResume : force ? io::RunOpening::kForce : io::RunOpening::kNewRun);
        else if (resume)
          throw InvalidInput("resume=True needs a run_directory");
        std::shared_ptr<const Case> source;
        if (run && resume) {
          source = py::module_::import("frictopt").attr("load_case")(run->store_case()).cast<std::shared_ptr<Case>>();
          if (!case_object.is_none()) {  // a case given on resume must be the run's problem
            const auto& given = case_object.cast<const Case&>().description;
            io::CaseFingerprint a, b;
            a.dim = given.dim();
            a.settings = given.problem_settings;
            b.dim = source->description.dim();
            b.settings = source->description.problem_settings;
            if (const auto changes = a.differences_from(b); !changes.empty())
              throw InvalidInput(fmt::format("resume: the case {} is not the case of the run in {}: {}; pass case=None",
                                             given.origin, run->path().string(), fmt::join(changes, "; ")));
          }
        } else if (case_object.is_none()) {
          throw InvalidInput("optimize: pass a case (or a run_directory with resume=True)");
        } else {
          source = case_object.cast<std::shared_ptr<Case>>();
          if (run) run->write_text_file(io::RunDirectory::kCaseCopy, source->toml);
        }
        const io::CaseDescription& description = source->description;
        const std::string case_name = run ? run->file(io::RunDirectory::kCaseCopy).string() : description.origin;
        const study::BodyDefinition& definition = description.body;
        if (!definition.contact) throw InvalidInput(case_name + ": optimize needs a [contact] table");

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
        study::require_admissible_design(*body, definition.initial_design, 1e-9, case_name + ": design.initial");
        const io::CaseFingerprint fingerprint = io::fingerprint_of(description, *body);
        std::optional<io::RunCheckpoint> checkpoint;
        if (resume) {
          checkpoint = run->read_checkpoint();
          run->check_resume(description, *checkpoint, fingerprint);
        }
        {
          py::gil_scoped_release release;
          oracle = std::make_unique<study::ShapeOracle>(*body, description.required_cost());
        }
        std::vector<std::string> notes;
        std::optional<io::CsvWriter> history;
        const int start_iteration = checkpoint ? checkpoint->method.iteration : 0;
        if (run) {
          history.emplace(run->open_history(kHistoryColumns, start_iteration, notes));
          run->start_series(definition.name, start_iteration, notes);
        }
        const auto write_design_vtu = [&](int iteration, const Eigen::VectorXd& alpha) {
          if (!run || !description.output.vtk) return;
          // Output must not change the numbers: restore the warm start a picture's solve moves.
          const auto warm_start = body->warm_start();
          run->add_to_series(iteration, [&](const fs::path& vtu) { io::write_state_vtu(vtu, *body, oracle->state(alpha)); });
          body->set_warm_start(warm_start);
        };
        // The run's counters continue over resumes.
        const double elapsed_offset = checkpoint ? checkpoint->elapsed_seconds : 0.0;
        const std::int64_t solves_offset = checkpoint ? checkpoint->state_solves : 0;
        double initial_value = kNaN;

        // A Python exception (from the callback, or KeyboardInterrupt from Ctrl-C) stops the run
        // at the end of the iteration; it is raised again once the run directory is complete.
        std::optional<py::error_already_set> pending;
        const auto on_progress = [&](const study::OptimizationProgress& p) {
          const auto& method = p.method;
          const double elapsed = elapsed_offset + p.elapsed_seconds;
          const std::int64_t solves = solves_offset + p.state_solves;
          const auto row = history_row(p, solves, elapsed);
          if (run) {
            history->write_row(row);
            if (method.iteration % description.output.every == 0) write_design_vtu(method.iteration, method.x);
            // Last, so that the checkpoint holds the state the next iteration starts from.
            io::RunCheckpoint c;
            c.method = method;
            c.fingerprint = fingerprint;
            if (const auto& warm = body->warm_start()) {
              c.warm_start = warm->z;
              c.warm_start_dim = warm->dim;
            }
            c.initial_cost = initial_value;
            c.elapsed_seconds = elapsed;
            c.state_solves = solves;
            run->write_checkpoint(c);
          }
          py::gil_scoped_acquire acquire;
          if (PyErr_CheckSignals() != 0) {  // Ctrl-C arrived while C++ was working
            pending.emplace();
            return CallbackResult::kStop;
          }
          if (callback.is_none()) return CallbackResult::kContinue;
          try {
            const py::object result = callback(progress_to_python(row, p));
            if (result.is(py::bool_(false))) return CallbackResult::kStop;
          } catch (py::error_already_set& e) {
            if (!e.matches(PyExc_StopIteration)) pending.emplace(std::move(e));
            return CallbackResult::kStop;
          }
          return CallbackResult::kContinue;
        };

        optim::BundleTrust::Summary summary;
        study::Evaluation final;
        {
          py::gil_scoped_release release;
          if (checkpoint) {
            initial_value = checkpoint->initial_cost;
            if (checkpoint->warm_start.size() > 0) {
              contact::ContactState warm(checkpoint->warm_start_dim,
                                         checkpoint->warm_start.size() / checkpoint->warm_start_dim);
              warm.z = checkpoint->warm_start;
              body->set_warm_start(std::move(warm));
            } else {
              body->set_warm_start(std::nullopt);
            }
          } else {
            // Θ(α⁰) for the summary, now: the method's first evaluation then hits the cache.
            initial_value = oracle->evaluate_design(definition.initial_design, true).value;
            write_design_vtu(0, definition.initial_design);
          }
          summary = study::optimize(*oracle, options, on_progress, checkpoint ? &checkpoint->method : nullptr);
          final = oracle->evaluate_design(summary.x, true);
          if (run && !run->series_has(summary.iterations)) write_design_vtu(summary.iterations, summary.x);
        }
        // The summary.json of `frictopt optimize` (same keys).
        io::JsonValue json = io::JsonValue::object();
        json["case"] = case_name;
        json["command"] = "optimize";
        json["cost"] = oracle->cost().name();
        json["status"] = std::string(to_string(summary.status));
        json["message"] = summary.message;
        json["stopped_by"] = io::to_json(summary).at("stopped_by");
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
        json["final_contact_solve"] = io::to_json(final.contact);
        json["optimizer"] = io::to_json(summary);
        if (run) {
          io::JsonValue design = io::JsonValue::object();
          design["alpha"] = summary.x;
          run->write_json_file(io::RunDirectory::kFinalDesign, design);
          run->write_json_file(io::RunDirectory::kSummary, json);
        }
        if (pending) throw std::move(*pending);

        py::object result = to_python(json);
        // The per-iteration history of this process as numpy columns.
        py::dict columns;
        const auto column = [&](auto field) {
          Eigen::VectorXd v(static_cast<Eigen::Index>(summary.history.size()));
          for (std::size_t k = 0; k < summary.history.size(); ++k) v(static_cast<Eigen::Index>(k)) = field(summary.history[k]);
          return to_numpy(v);
        };
        columns["iteration"] = column([](const auto& h) { return static_cast<double>(h.iteration); });
        columns["evaluations"] = column([](const auto& h) { return static_cast<double>(h.evaluations); });
        columns["theta"] = column([](const auto& h) { return h.f; });
        columns["t"] = column([](const auto& h) { return h.t; });
        columns["stationarity_relative"] = column([](const auto& h) { return h.stationarity; });
        result.attr("__setitem__")("history", py::module_::import("frictopt._summary").attr("Summary")(columns));
        result.attr("__setitem__")("run_directory", run ? py::cast(run->path()) : py::none());
        result.attr("__setitem__")("notes", py::cast(notes));
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

run_directory: when given, the CLI's run directory (docs/case-format.md, "Run directories"):
case.toml, history.csv, checkpoint.json, a VTK series every [output].every iterations,
final_design.json, summary.json, locked against a second process. A directory holding a run is
refused unless resume=True (continue from its checkpoint with its case.toml, bit for bit; a
``case`` given then must be the same problem) or force=True (remove that run's files; a foreign
file is refused). max_iterations, max_evaluations and epsilon override the case's
[optimization] values.

Returns a Summary with the fields of the CLI's summary.json (status, message, stopped_by,
initial_cost, final_cost, alpha, iterations, evaluations, stationarity, optimizer, ...) plus
history (numpy columns), run_directory and notes (what the run directory reported on resume).
Non-convergence is a status, not an exception.)doc");
}

}  // namespace frictopt::python
