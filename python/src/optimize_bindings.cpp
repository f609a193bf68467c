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
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/optimization_run.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace frictopt::python {

namespace {

// The progress object given to callbacks: the history.csv row (same names) plus α.
py::object progress_to_python(const std::vector<io::CsvValue>& row, const study::OptimizationProgress& p) {
  const auto& columns = io::optimization_history_columns();
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
          // The CLI's copy (RunDirectory::store_case): relative file names made absolute, so
          // that `frictopt optimize --resume` and `certify` read the same mesh.
          if (run) run->store_case_text(source->toml, source->description.origin);
        }
        io::OptimizationRunRequest request;
        request.description = source->description;
        request.case_name = run ? run->file(io::RunDirectory::kCaseCopy).string() : source->description.origin;
        request.run = run ? &*run : nullptr;
        request.resume = resume;
        optim::BundleTrust::Options options = source->description.optimization;
        override_option(options.max_iterations, max_iterations);
        override_option(options.max_evaluations, max_evaluations);
        override_option(options.epsilon, epsilon);
        request.options = options;

        // A Python exception (from the callback, or KeyboardInterrupt from Ctrl-C) stops the run
        // at the end of the iteration; it is raised again once the run directory is complete.
        std::optional<py::error_already_set> pending;
        request.on_iteration = [&](const std::vector<io::CsvValue>& row, const study::OptimizationProgress& p) {
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
        io::OptimizationRunResult run_result;
        {
          py::gil_scoped_release release;
          run_result = io::run_optimization(request);
        }
        if (pending) throw std::move(*pending);
        const optim::BundleTrust::Summary& summary = run_result.summary;
        const std::vector<std::string>& notes = run_result.notes;

        py::object result = to_python(run_result.summary_json);
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
