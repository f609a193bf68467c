// SPDX-License-Identifier: MIT
// frictopt.identify and friends: friction coefficients (and E) from measured contact quantities
// (study::Identification, Ceres; docs/identification.md), as `frictopt identify`.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/measurements.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/identification.hpp"

namespace frictopt::python {

namespace {

const io::IdentificationSetup& setup_of(const Case& c) {
  if (!c.description.identification)
    throw InvalidInput(c.description.origin + ": identify needs an [identification] table (docs/identification.md)");
  return *c.description.identification;
}

// Measurements from Python: a CSV path, or a sequence of Measurement objects, dicts of
// Measurement's keyword arguments or tuples of its positional ones.
std::vector<study::Measurement> to_measurements(const py::module_& m, const py::object& rows) {
  if (py::isinstance<py::str>(rows) || py::hasattr(rows, "__fspath__"))
    return io::read_measurements(rows.cast<std::filesystem::path>());
  if (!py::isinstance<py::sequence>(rows))
    throw InvalidInput(fmt::format("measurements = {}; expected a CSV path or a list of Measurement (or of dicts or "
                                   "tuples of its arguments)",
                                   py::repr(rows).cast<std::string>()));
  std::vector<study::Measurement> out;
  const py::object make = m.attr("Measurement");
  for (const py::handle item : rows) {
    if (py::isinstance<py::dict>(item)) out.push_back(make(**py::reinterpret_borrow<py::dict>(item)).cast<study::Measurement>());
    else if (py::isinstance<py::tuple>(item)) out.push_back(make(*py::reinterpret_borrow<py::tuple>(item)).cast<study::Measurement>());
    else out.push_back(item.cast<study::Measurement>());
  }
  return out;
}

// A scale: None (every scale 1), a number (every table of its kind) or one per table.
std::vector<double> to_scales(const py::object& value) {
  if (value.is_none()) return {};
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) return {value.cast<double>()};
  return value.cast<std::vector<double>>();
}

// The experiments of an identification: `experiments` (Experiment objects or dicts of its
// arguments), or one with `measurements` and the case's own loads, or the case's own.
std::vector<study::IdentificationExperiment> experiments_of(const py::module_& m, const Case& c,
                                                            const py::object& measurements,
                                                            const py::object& experiments) {
  const io::IdentificationSetup& setup = setup_of(c);
  if (!experiments.is_none()) {
    if (!measurements.is_none())
      throw InvalidInput("give measurements or experiments, not both (each experiment holds its own measurements)");
    std::vector<study::IdentificationExperiment> out;
    const py::object make = m.attr("Experiment");
    for (const py::handle item : experiments) {
      if (py::isinstance<py::dict>(item)) out.push_back(make(**py::reinterpret_borrow<py::dict>(item)).cast<study::IdentificationExperiment>());
      else out.push_back(item.cast<study::IdentificationExperiment>());
    }
    return out;
  }
  if (measurements.is_none()) return io::identification_experiments(setup, c.description.origin);
  if (setup.explicit_experiments)
    throw InvalidInput(fmt::format("{}: the case has {} [[identification.experiment]] tables, each with its own loads and "
                                   "measurements; expected experiments=[...] (one measurement list per experiment)",
                                   c.description.origin, setup.experiments.size()));
  study::IdentificationExperiment x = io::experiment_loads(setup.experiments.front());
  x.measurements = to_measurements(m, measurements);
  return {x};
}

// The experiments with synthetic values: the case's own law's prediction (raises when the model
// cannot be evaluated there) plus noise, as `frictopt identify --generate-synthetic`.
std::vector<study::IdentificationExperiment> synthetic_of(const Case& source,
                                                          std::vector<study::IdentificationExperiment> experiments,
                                                          std::uint64_t seed, bool noise) {
  study::Identification identification(source.description.body, experiments, setup_of(source).options);
  study::Identification::Prediction exact;
  {
    py::gil_scoped_release release;
    exact = identification.predict(identification.case_parameters());
  }
  if (!exact.ok) throw std::runtime_error("the model could not be evaluated at the case's parameters: " + exact.message);
  return study::synthetic_experiments(std::move(experiments), exact.values, seed, noise);
}

}  // namespace

void bind_identification(py::module_& m) {
  py::class_<study::Measurement>(m, "Measurement", R"doc(
One measured contact quantity with its standard deviation σ (same unit). Quantities:
'normal_force' [N], 'pressure' [Pa], 'tangential_force_x1/x2' [N], 'traction_x1/x2' [Pa],
'slip_x1/x2' [m] at a contact node (``node`` index, or the nearest to ``point`` x' [m]), and the
totals 'total_normal_force', 'total_tangential_force_x1/x2' [N] over Γ_c (no location).
Forces and tractions are those the foundation exerts on the body.
)doc")
      .def(py::init([](const std::string& quantity, double value, double sigma, int node,
                       std::optional<Eigen::VectorXd> point, std::string label) {
             study::Measurement me;
             me.quantity = study::parse_measured_quantity(quantity);
             me.value = value;
             me.sigma = sigma;
             me.node = node;
             me.point = std::move(point);
             me.label = std::move(label);
             return me;
           }),
           py::arg("quantity"), py::arg("value"), py::arg("sigma") = 1.0, py::arg("node") = -1,
           py::arg("point") = py::none(), py::arg("label") = "python")
      .def_property_readonly("quantity", [](const study::Measurement& me) { return std::string(study::to_string(me.quantity)); },
                             "The measured quantity's name.")
      .def_readwrite("value", &study::Measurement::value, "Measured value (unit of the quantity).")
      .def_readwrite("sigma", &study::Measurement::sigma, "Standard deviation σ > 0 (same unit).")
      .def_readwrite("node", &study::Measurement::node, "Contact-node index, or −1.")
      .def_readwrite("point", &study::Measurement::point, "In-plane location x' [m] (nearest contact node), or None.")
      .def_readwrite("label", &study::Measurement::label, "Where it came from, for messages.")
      .def("__repr__", [](const study::Measurement& me) {
        return fmt::format("<frictopt.Measurement {} node {} = {:.8g} ± {:.3g} ({})>", study::to_string(me.quantity),
                           me.node, me.value, me.sigma, me.label);
      });

  py::class_<study::IdentificationExperiment>(m, "Experiment", R"doc(
One experiment of an identification (docs/identification.md, "Several experiments"): the case's
body under its loads scaled by load_scale / dirichlet_scale / force_scale (a number for every
[[load]] / [[dirichlet]] / [[force]] table, or one per table; None: 1), with the friction law
turned by orientation_deg in the contact plane (the specimen turned on the tribometer), and its
own measurements (a list of Measurement, of dicts or tuples of Measurement's arguments, or a CSV
path). The identified coefficients are those of the specimen's own frame, shared by every
experiment.
)doc")
      .def(py::init([m](const std::string& name, const py::object& measurements, double orientation_deg,
                        const py::object& load_scale, const py::object& dirichlet_scale, const py::object& force_scale) {
             study::IdentificationExperiment x;
             x.name = name;
             x.measurements = to_measurements(m, measurements);
             if (!std::isfinite(orientation_deg))
               throw InvalidInput(fmt::format("orientation_deg = {}; expected a finite angle [degrees]", orientation_deg));
             x.orientation = orientation_deg * std::numbers::pi / 180.0;
             x.load_scale = to_scales(load_scale);
             x.dirichlet_scale = to_scales(dirichlet_scale);
             x.force_scale = to_scales(force_scale);
             return x;
           }),
           py::arg("name"), py::arg("measurements"), py::arg("orientation_deg") = 0.0, py::arg("load_scale") = py::none(),
           py::arg("dirichlet_scale") = py::none(), py::arg("force_scale") = py::none())
      .def_readwrite("name", &study::IdentificationExperiment::name, "Its name in reports (unique).")
      .def_readwrite("measurements", &study::IdentificationExperiment::measurements, "Its measurements.")
      .def_property(
          "orientation_deg",
          [](const study::IdentificationExperiment& x) { return x.orientation * 180.0 / std::numbers::pi; },
          [](study::IdentificationExperiment& x, double deg) { x.orientation = deg * std::numbers::pi / 180.0; },
          "The friction law's turn in the contact plane [degrees].")
      .def_readwrite("load_scale", &study::IdentificationExperiment::load_scale, "Scales of the [[load]] tables ([]: 1).")
      .def_readwrite("dirichlet_scale", &study::IdentificationExperiment::dirichlet_scale,
                     "Scales of the [[dirichlet]] displacements ([]: 1).")
      .def_readwrite("force_scale", &study::IdentificationExperiment::force_scale, "Scales of the [[force]] tables ([]: 1).")
      .def("__repr__", [](const study::IdentificationExperiment& x) {
        return fmt::format("<frictopt.Experiment '{}': {} measurements, orientation {:g} deg>", x.name,
                           x.measurements.size(), x.orientation * 180.0 / std::numbers::pi);
      });

  m.def("read_measurements", &io::read_measurements, py::arg("path"),
        "Reads a measurement CSV (quantity,location,value,sigma; docs/identification.md) into Measurements.");
  m.def(
      "write_measurements",
      [](const std::filesystem::path& path, const std::vector<study::Measurement>& ms, const std::string& comment) {
        io::write_measurements(path, ms, comment);
      },
      py::arg("path"), py::arg("measurements"), py::arg("comment") = "",
      "Writes measurements in the CSV format read_measurements reads.");

  m.def(
      "synthetic_measurements",
      [m](std::shared_ptr<const Case> source, const py::object& templates, std::uint64_t seed, bool noise) {
        const auto experiments = experiments_of(m, *source, templates, py::none());
        if (experiments.size() != 1)
          throw InvalidInput(fmt::format("{}: the case has {} [[identification.experiment]] tables; expected "
                                         "synthetic_experiments(case) for them",
                                         source->description.origin, experiments.size()));
        return synthetic_of(*source, experiments, seed, noise).front().measurements;
      },
      py::arg("case"), py::arg("templates") = py::none(), py::arg("seed") = 1, py::arg("noise") = true,
      "Measurements at the rows of `templates` (default: the case's measurements) with values of the\n"
      "case's own friction law plus N(0, σ²) noise (seeded; noise=False: exact), as\n"
      "``frictopt identify --generate-synthetic``.");

  m.def(
      "synthetic_experiments",
      [m](std::shared_ptr<const Case> source, const py::object& experiments, std::uint64_t seed, bool noise) {
        return synthetic_of(*source, experiments_of(m, *source, py::none(), experiments), seed, noise);
      },
      py::arg("case"), py::arg("experiments") = py::none(), py::arg("seed") = 1, py::arg("noise") = true,
      "The experiments (default: the case's, [[identification.experiment]] or its own loads) with the values\n"
      "of their measurements replaced by the case's own friction law's plus N(0, σ²) noise (one seeded\n"
      "stream over all rows in order, as ``frictopt identify --generate-synthetic``).");

  m.def(
      "identify",
      [m](std::shared_ptr<const Case> source, const py::object& measurements, const py::object& experiments) {
        const auto list = experiments_of(m, *source, measurements, experiments);
        study::Identification identification(source->description.body, list, setup_of(*source).options);
        study::Identification::Summary s;
        {
          py::gil_scoped_release release;
          s = identification.run();
        }
        // The summary.json of `frictopt identify` (same keys), plus arrays.
        io::JsonValue summary = io::JsonValue::object();
        summary["case"] = source->description.origin;
        summary["command"] = "identify";
        io::add_members(summary, io::run_environment());
        io::add_members(summary, io::to_json(s));
        py::object result = to_python(summary);
        result.attr("__setitem__")("predictions", to_numpy(s.predictions));
        result.attr("__setitem__")("residuals", to_numpy(s.residuals));
        result.attr("__setitem__")("covariance", to_numpy(s.covariance));
        result.attr("__setitem__")("contact_coordinates", to_numpy(identification.contact_coordinates()));
        return result;
      },
      py::arg("case"), py::arg("measurements") = py::none(), py::kw_only(), py::arg("experiments") = py::none(),
      R"doc(Identifies the friction coefficients (and E) named in the case's [identification] table by
weighted least squares with Ceres (docs/identification.md), from
- measurements: a list of Measurement (or of dicts / tuples of its arguments) or a CSV path, with
  the case's own loads — no measurement file needs to be named in the case; or
- experiments: a list of Experiment (or of dicts of its arguments), each with its own loads,
  specimen orientation and measurements, fitted jointly; or
- neither: the case's own measurements (its CSV, inline rows or [[identification.experiment]]s).
Returns a Summary with the fields of the CLI's summary.json (status, estimates [name, value,
standard_deviation, identifiability, ...], chi_square, correlation, singular_values, experiments
[name, measurements, chi_square, rms_residual, ...], ...) plus predictions, residuals (normalized by
σ), covariance and contact_coordinates [m]. Non-convergence is a status.)doc");
}

}  // namespace frictopt::python
