// SPDX-License-Identifier: MIT
// Shared pieces of the Python bindings (docs/python.md): the objects that own C++ state on
// behalf of Python, the numpy-view helper and one bind_* function per concept. The bindings
// call the high-level API only (io::parse_case / load_case, study::ElasticBody, ShapeOracle,
// optimize, certify, Identification, io writers); mesh internals are not exposed.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "frictopt/io/case_description.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::python {

namespace py = pybind11;

/// A validated case and the TOML text it was parsed from (kept so that Python can derive
/// modified cases through the same parser, and so that a run directory stores what was run).
struct Case {
  io::CaseDescription description;
  std::string toml;
};

/// One body on its fixed mesh (study::ElasticBody) and what Python reads about it repeatedly.
/// The mutex serializes solves: the GIL is released while C++ works, and the body reuses its
/// factorization, so two Python threads must not solve on it at once.
struct Body {
  std::shared_ptr<const Case> source;
  std::unique_ptr<study::ElasticBody> body;
  Eigen::VectorXd tributary_areas;  // per contact node [m², 2D: m]
  std::mutex mutex;
};

/// The state of a body at one design, shared with the numpy views taken of it.
struct State {
  std::shared_ptr<const study::BodyState> state;
  std::shared_ptr<Body> body;
};

/// The oracle Θ(α) on its own body (so Body.solve cannot disturb the factorization the
/// oracle's adjoint relies on).
struct Oracle {
  std::shared_ptr<const Case> source;
  std::unique_ptr<study::ElasticBody> body;
  std::unique_ptr<study::ShapeOracle> oracle;
  std::mutex mutex;
};

/// A read-only numpy array over `data` (no copy), kept alive by `owner` (numpy's base object).
/// Shape and strides are in elements of double.
py::array readonly_view(const double* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                        py::handle owner);
/// A numpy copy of a vector / matrix (for small or derived arrays).
py::array to_numpy(const Eigen::VectorXd& v);
py::array to_numpy(const Eigen::MatrixXd& m);
/// The JSON value as Python objects (objects → frictopt.Summary, arrays of numbers → numpy,
/// NaN stays NaN).
py::object to_python(const io::JsonValue& value);
/// α from Python (sequence or array of floats); None → `fallback`. Throws InvalidInput when the
/// size is not `expected` (naming `what`).
Eigen::VectorXd design_from_python(const py::object& alpha, const Eigen::VectorXd& fallback, const char* what);
/// A RuntimeWarning naming the violated constraint when α is outside Υ (by more than 1e-9 m).
void warn_if_outside(const study::ElasticBody& body, const Eigen::VectorXd& alpha, const char* what);

/// The optimizer's x⁰ of a case: α⁰, or (α⁰, s⁰ = kφ⁰) with [design] friction_orientation (as
/// study::ElasticBody::initial_design, without building the body; its size is the number of
/// design variables).
Eigen::VectorXd case_initial_design(const io::CaseDescription& description);

/// The summary.json of `frictopt solve` for `state` (the same keys and values as the CLI).
io::JsonValue solve_summary_json(const Case& source, const study::ElasticBody& body, const study::BodyState& state);

void bind_case(py::module_& m);
void bind_friction_law(py::module_& m);
void bind_body(py::module_& m);
void bind_oracle(py::module_& m);
void bind_optimize(py::module_& m);
void bind_identification(py::module_& m);
void bind_experiment(py::module_& m);
void bind_shape_export(py::module_& m);

}  // namespace frictopt::python
