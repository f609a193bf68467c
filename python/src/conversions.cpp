// SPDX-License-Identifier: MIT
// numpy views and copies, JSON → Python, designs from Python (bindings.hpp).
#include <pybind11/numpy.h>

#include <fmt/format.h>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/study/orientation_design.hpp"

namespace frictopt::python {

py::array readonly_view(const double* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                        py::handle owner) {
  for (auto& s : strides) s *= static_cast<py::ssize_t>(sizeof(double));
  // numpy's base object is `owner`: the C++ state lives as long as any view of it.
  py::array view(py::dtype::of<double>(), std::move(shape), std::move(strides), data, owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

py::array to_numpy(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

py::array to_numpy(const Eigen::MatrixXd& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  auto r = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) r(i, j) = m(i, j);
  return out;
}

py::object to_python(const io::JsonValue& value) {
  if (value.is_null()) return py::none();
  if (value.is_bool()) return py::bool_(value.as_bool());
  if (value.is_integer()) return py::int_(value.as_integer());
  if (value.is_real()) return py::float_(value.as_number());
  if (value.is_string()) return py::str(value.as_string());
  if (value.is_array()) {
    const auto& items = value.as_array();
    const bool numbers = !items.empty() && std::all_of(items.begin(), items.end(), [](const io::JsonValue& v) {
      return v.is_real() || v.is_integer();
    });
    if (numbers && std::any_of(items.begin(), items.end(), [](const io::JsonValue& v) { return v.is_real(); })) {
      Eigen::VectorXd v(static_cast<Eigen::Index>(items.size()));
      for (std::size_t k = 0; k < items.size(); ++k) v(static_cast<Eigen::Index>(k)) = items[k].as_number();
      return to_numpy(v);
    }
    py::list list;
    for (const auto& item : items) list.append(to_python(item));
    return list;
  }
  py::dict dict;
  for (const auto& [key, item] : value.as_object()) dict[py::str(key)] = to_python(item);
  return py::module_::import("frictopt._summary").attr("Summary")(dict);
}

Eigen::VectorXd design_from_python(const py::object& alpha, const Eigen::VectorXd& fallback, const char* what) {
  if (alpha.is_none()) return fallback;
  // numpy's forcecast below would drop an imaginary part silently.
  if (py::module_::import("numpy").attr("iscomplexobj")(alpha).cast<bool>())
    throw InvalidInput(fmt::format("{}: complex values; expected {} real numbers (m)", what, fallback.size()));
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(alpha);
  if (!array || array.ndim() != 1)
    throw InvalidInput(fmt::format("{}: expected a 1-D sequence of {} numbers (m)", what, fallback.size()));
  if (array.shape(0) != fallback.size())
    throw InvalidInput(fmt::format("{} has {} entries; expected {} (one per design variable)", what, array.shape(0),
                                   fallback.size()));
  return Eigen::Map<const Eigen::VectorXd>(array.data(), array.shape(0));
}

Eigen::VectorXd case_initial_design(const io::CaseDescription& description) {
  const study::BodyDefinition& b = description.body;
  if (!b.friction_orientation || !b.contact) return b.initial_design;
  return study::OrientationDesign(*b.friction_orientation, b.contact->law, b.admissible.upper_bound)
      .initial_design(b.initial_design);
}

void warn_if_outside(const study::ElasticBody& body, const Eigen::VectorXd& alpha, const char* what) {
  // The CLI's solve warns for an initial design outside Υ, certify and check-gradient refuse one;
  // an API that evaluates any design (finite differences cross the volume equality) says so
  // instead of staying silent (a design 1 m below the foundation "converged").
  const std::string violation = body.admissible_set().describe_violation(alpha, 1e-9);
  if (violation.empty()) return;
  const std::string message = fmt::format("{} is outside the admissible set: {} (solved anyway; certify and "
                                          "check_gradient refuse such a design)",
                                          what, violation);
  if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

}  // namespace frictopt::python
