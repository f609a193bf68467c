// SPDX-License-Identifier: MIT
// frictopt.identify and friends: friction coefficients (and E) from measured contact quantities
// (study::Identification, Ceres; docs/identification.md), as `frictopt identify`.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>

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

std::vector<study::Measurement> measurements_of(const Case& c, const py::object& measurements) {
  if (measurements.is_none()) return io::read_measurements(setup_of(c).measurements);
  if (py::isinstance<py::str>(measurements) || py::hasattr(measurements, "__fspath__"))
    return io::read_measurements(measurements.cast<std::filesystem::path>());
  return measurements.cast<std::vector<study::Measurement>>();
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
      [](std::shared_ptr<const Case> source, const py::object& templates, std::uint64_t seed, bool noise) {
        const auto rows = measurements_of(*source, templates);
        study::Identification identification(source->description.body, rows, setup_of(*source).options);
        study::Identification::Prediction exact;
        {
          py::gil_scoped_release release;
          exact = identification.predict(identification.case_parameters());
        }
        if (!exact.ok)
          throw std::runtime_error("the model could not be evaluated at the case's parameters: " + exact.message);
        return study::synthetic_measurements(rows, exact.values, seed, noise);
      },
      py::arg("case"), py::arg("templates") = py::none(), py::arg("seed") = 1, py::arg("noise") = true,
      "Measurements at the rows of `templates` (default: the case's measurement file) with values of the\n"
      "case's own friction law plus N(0, σ²) noise (seeded; noise=False: exact), as\n"
      "``frictopt identify --generate-synthetic``.");

  m.def(
      "identify",
      [](std::shared_ptr<const Case> source, const py::object& measurements) {
        const auto rows = measurements_of(*source, measurements);
        study::Identification identification(source->description.body, rows, setup_of(*source).options);
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
      py::arg("case"), py::arg("measurements") = py::none(),
      R"doc(Identifies the friction coefficients (and E) named in the case's [identification] table from
measurements (a list of Measurement, a CSV path, or None for the case's file) by weighted least
squares with Ceres (docs/identification.md). Returns a Summary with the fields of the CLI's
summary.json (status, estimates [name, value, standard_deviation, identifiability, ...],
chi_square, correlation, singular_values, ...) plus predictions, residuals (normalized by σ),
covariance and contact_coordinates [m]. Non-convergence is a status.)doc");
}

}  // namespace frictopt::python
