// SPDX-License-Identifier: MIT
// frictopt.experiment: the virtual tribometer of a case's [experiment] table (io::run_experiment,
// the same run as `frictopt experiment`), with an optional run directory that gets the CLI's
// files, and the angles' ramps returned as numpy columns; frictopt.solve_program: a case's loading
// program (io::run_loading_program, the same run as `frictopt solve` of such a case).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <functional>
#include <optional>

#include "bindings.hpp"
#include "frictopt/io/experiment_run.hpp"
#include "frictopt/io/program_run.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"

namespace frictopt::python {
namespace {

// The run's opener for an optional run_directory argument (none: nothing written). As the CLI's:
// created if missing, frictopt's files in it replaced, foreign ones kept.
std::function<io::RunDirectory*()> run_opener(const py::object& run_directory, std::optional<io::RunDirectory>& run) {
  if (run_directory.is_none()) return {};
  const std::filesystem::path dir = run_directory.cast<std::filesystem::path>();
  return [&run, dir]() -> io::RunDirectory* { return &run.emplace(dir, io::RunOpening::kOutput); };
}

}  // namespace

void bind_experiment(py::module_& m) {
  m.def(
      "experiment",
      [](std::shared_ptr<const Case> source, const py::object& run_directory) {
        std::optional<io::RunDirectory> run;
        io::ExperimentRunRequest request{source->description, source->description.origin, {}, {}};
        request.open_run = run_opener(run_directory, run);
        io::ExperimentRunResult result;
        {
          py::gil_scoped_release release;
          result = io::run_experiment(request);
        }
        // summary.json's fields, each angle with its ramp as numpy columns.
        py::object summary = to_python(result.summary_json);
        py::list angles;
        const py::object make_summary = py::module_::import("frictopt._summary").attr("Summary");
        for (const study::TribometerAngleResult& a : result.summary.angles) {
          py::object angle = to_python(io::to_json(a));
          const auto n = static_cast<Eigen::Index>(a.ramp.size());
          Eigen::VectorXd pull(n), normal(n), t1(n), t2(n), stick(n);
          for (Eigen::Index k = 0; k < n; ++k) {
            const auto& pt = a.ramp[static_cast<std::size_t>(k)];
            pull(k) = pt.pull;
            normal(k) = pt.normal_force;
            t1(k) = pt.tangential_force(0);
            t2(k) = pt.tangential_force(1);
            stick(k) = pt.stick_fraction;
          }
          py::dict ramp;
          ramp["pull"] = to_numpy(pull);
          ramp["normal_force"] = to_numpy(normal);
          ramp["tangential_force_x1"] = to_numpy(t1);
          ramp["tangential_force_x2"] = to_numpy(t2);
          ramp["stick_fraction"] = to_numpy(stick);
          angle.attr("__setitem__")("ramp", make_summary(ramp));
          angles.append(angle);
        }
        summary.attr("__setitem__")("angles", angles);
        summary.attr("__setitem__")("run_directory", run ? py::cast(run->path()) : py::none());
        return summary;
      },
      py::arg("case"), py::arg("run_directory") = py::none(),
      R"doc(Runs the virtual tribometer of the case's [experiment] table (docs/experiments.md), as
``frictopt experiment``: the specimen is pressed to normal_force and pulled along each of
angles_degrees (by the platen's displacement or by a force), and the friction law is read from
the sliding state.

run_directory: when given, the CLI's files (tribometer_ramp.csv, tribometer_polar.csv,
tribometer_law.csv, summary.json); created if missing, frictopt's files in it are replaced.

Returns a Summary with the fields of the CLI's summary.json (status, message, drive,
press_displacement, contact_solves, factorizations, time_seconds, ...) and angles: one Summary
per angle (angle_degrees, gross_sliding, onset_step, onset_force, steady_sliding,
sliding_force, measured_mu, law_mu (the radial μ(φ)), law_resistance (the support N_W(ŝ)),
relative_error, normality_residual, ...) with its ramp as numpy columns (pull,
normal_force, tangential_force_x1, tangential_force_x2, stick_fraction). A solve that does not
converge is a status, not an exception.)doc");

  m.def(
      "solve_program",
      [](std::shared_ptr<const Case> source, const py::object& run_directory) {
        std::optional<io::RunDirectory> run;
        io::ProgramRunRequest request{source->description, source->description.origin, {}, {}};
        request.open_run = run_opener(run_directory, run);
        io::ProgramRunResult result;
        {
          py::gil_scoped_release release;
          result = io::run_loading_program(request);
        }
        py::object summary = to_python(result.summary_json);
        summary.attr("__setitem__")("run_directory", run ? py::cast(run->path()) : py::none());
        return summary;
      },
      py::arg("case"), py::arg("run_directory") = py::none(),
      R"doc(Solves the case's loading program ([[program.step]] tables, docs/experiments.md) at its
initial design, as ``frictopt solve`` of such a case: the steps in order from the unloaded body,
each on the one factorization, friction acting on each step's slip increment.

run_directory: when given, the CLI's files (the VTK series NAME.pvd of the steps, summary.json);
created if missing, frictopt's files in it are replaced.

Returns a Summary with the fields of the CLI's summary.json (status, message, steps_solved,
factorizations, factorization_seconds, contact_seconds, time_seconds, and steps: one Summary per
step with the solve's fields, step, label and external_work). A step that does not converge ends
the run with its status, not an exception; a case without [[program.step]] tables raises
ValueError.)doc");
}

}  // namespace frictopt::python
