// SPDX-License-Identifier: MIT
// frictopt.FrictionLaw: the friction set W of contact::FrictionLaw (docs/contact.md): both μ(θ)
// (the support function N_W along a direction and the radial function of W), vertices,
// projection onto s·W.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <cmath>

#include "bindings.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::python {

namespace {

using contact::FrictionLaw;

// Rows of 2-vectors as an (n, 2) array.
py::array rows(std::span<const Eigen::Vector2d> points) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t j = 0; j < points.size(); ++j) out.row(static_cast<Eigen::Index>(j)) = points[j].transpose();
  return to_numpy(out);
}

// A tangential vector from Python: a float (2D laws) or two floats.
Eigen::Vector2d tangential(const py::object& u) {
  if (py::isinstance<py::float_>(u) || py::isinstance<py::int_>(u)) return {u.cast<double>(), 0.0};
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(u);
  if (!a || a.ndim() != 1 || a.shape(0) < 1 || a.shape(0) > 2)
    throw InvalidInput("expected a tangential vector: a float (2D) or a sequence of 2 floats");
  return {a.at(0), a.shape(0) == 2 ? a.at(1) : 0.0};
}

double support_mu(const FrictionLaw& l, double t) { return l.support(Eigen::Vector2d(std::cos(t), std::sin(t))); }

double radial_mu(const FrictionLaw& l, double t) {
  if (l.dim() == 2) {
    const double d = std::cos(t);  // the sign picks the end of the interval
    return d == 0.0 ? 0.0 : l.max_step(Eigen::Vector2d::Zero(), 1.0, Eigen::Vector2d(d, 0.0)) * std::abs(d);
  }
  return l.max_step(Eigen::Vector2d::Zero(), 1.0, Eigen::Vector2d(std::cos(t), std::sin(t)));
}

// f(law, θ) for a float θ or elementwise for an array of any shape.
py::object along_angles(const FrictionLaw& l, const py::object& theta, const char* name,
                        double (*f)(const FrictionLaw&, double)) {
  if (py::isinstance<py::float_>(theta) || py::isinstance<py::int_>(theta)) return py::float_(f(l, theta.cast<double>()));
  const auto in = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(theta);
  if (!in) throw InvalidInput(fmt::format("{}: theta must be a float or an array of floats (rad)", name));
  py::array_t<double> out(std::vector<py::ssize_t>(in.shape(), in.shape() + in.ndim()));
  double* o = out.mutable_data();
  for (py::ssize_t k = 0; k < in.size(); ++k) o[k] = f(l, in.data()[k]);
  return out;
}

}  // namespace

void bind_friction_law(py::module_& m) {
  py::class_<FrictionLaw>(m, "FrictionLaw", R"doc(
A friction law as its friction set W: the friction force q = −τ at a contact node lies in λ·W
(λ the normal force, N), and the friction coefficient in a sliding direction e is the support
function μ(e) = N_W(e) = max_{w ∈ W} ⟨w, e⟩ (dimensionless; docs/contact.md).

Construct with the static methods: ``interval(mu_minus, mu_plus)`` (2D), ``disc(mu)``,
``regular_polygon(mu, n)``, ``polygon(mu_vertices)``, ``ellipse(mu_x, mu_y)``,
``ellipse_polygon(mu_x, mu_y, n)`` (3D). Invalid coefficients raise ValueError.
)doc")
      .def_static("interval", &FrictionLaw::interval, py::arg("mu_minus"), py::arg("mu_plus"),
                  "2D law W = [−μ₋, μ₊]: sliding along +x₁ costs μ₊, along −x₁ costs μ₋.")
      .def_static("disc", &FrictionLaw::disc, py::arg("mu"), "3D isotropic Coulomb law: W = disc of radius μ.")
      .def_static("regular_polygon", &FrictionLaw::regular_polygon, py::arg("mu"), py::arg("n"),
                  "3D isotropic n-gon μ·conv{v_j}, v_j at angles φ_j = π(2j−1)/n, j = 1..n.")
      .def_static("polygon", &FrictionLaw::polygon, py::arg("mu_vertices"),
                  "3D anisotropic polygon conv{μ_j v_j} with the directions v_j of regular_polygon\n"
                  "(n = 4: the thesis' remark 6.2.1). Must be convex with every vertex a corner.")
      .def_static("ellipse", &FrictionLaw::ellipse, py::arg("mu_x"), py::arg("mu_y"),
                  "3D exact orthotropic law {(x/μ_x)² + (y/μ_y)² ≤ 1}.")
      .def_static("ellipse_polygon", &FrictionLaw::ellipse_polygon, py::arg("mu_x"), py::arg("mu_y"), py::arg("n"),
                  "3D n-gon with vertices (μ_x cos φ_j, μ_y sin φ_j) on the ellipse.")
      .def_property_readonly("kind", [](const FrictionLaw& l) { return std::string(contact::to_string(l.kind())); },
                             "'interval', 'disc', 'regular_polygon', 'polygon', 'ellipse' or 'ellipse_polygon'.")
      .def_property_readonly("dim", &FrictionLaw::dim, "Spatial dimension: 2 (interval) or 3.")
      .def_property_readonly("is_polygonal", &FrictionLaw::is_polygonal, "True for interval and polygon laws.")
      .def_property_readonly("is_zero", &FrictionLaw::is_zero, "True when W = {0} (frictionless).")
      .def_property_readonly("max_coefficient", &FrictionLaw::max_coefficient,
                             "Largest friction coefficient over all directions, max_{w∈W} |w|.")
      .def_property_readonly("vertices", [](const FrictionLaw& l) { return rows(l.vertices()); },
                             "Vertices w_j of W as an (n, 2) array, counter-clockwise (smooth sets: (0, 2)).")
      .def_property_readonly("edge_normals", [](const FrictionLaw& l) { return rows(l.edge_normals()); },
                             "Unit outward normals e_j of the edges [w_j, w_{j+1}], (n, 2) (polygons only).")
      .def_property_readonly(
          "edge_heights",
          [](const FrictionLaw& l) {
            const auto h = l.edge_heights();
            return to_numpy(Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(h.data(), static_cast<Eigen::Index>(h.size()))));
          },
          "Heights h_j = ⟨e_j, w_j⟩ of the edges (polygons only).")
      .def_property_readonly("semi_axes", [](const FrictionLaw& l) { return to_numpy(Eigen::VectorXd(l.semi_axes())); },
                             "Semi-axes (μ_x, μ_y) of an ellipse law; (μ, μ) for a disc.")
      // Two coefficients are called μ(θ) (docs/contact.md, "Two meanings of μ(θ)"): the resistance
      // to sliding along θ, N_W(e_θ) (support_mu; `mu` is this one), and the friction set's
      // boundary in direction θ, max{s : s e_θ ∈ W} (radial_mu): the largest friction force per
      // unit normal force that points along θ, which the tribometer's μ(θ)·P reads.
      .def(
          "mu", [](const FrictionLaw& l, const py::object& theta) { return along_angles(l, theta, "mu", support_mu); },
          py::arg("theta"),
          "Resistance to sliding along θ [rad]: μ(θ) = N_W((cos θ, sin θ)), the dissipation per unit\n"
          "normal force of a unit slip along θ (the same as support_mu). Not the friction set's boundary\n"
          "in direction θ (radial_mu): the two differ for an anisotropic law. A float or an array of any\n"
          "shape (2D laws: θ = 0 is +x₁, θ = π is −x₁).")
      .def(
          "support_mu",
          [](const FrictionLaw& l, const py::object& theta) { return along_angles(l, theta, "support_mu", support_mu); },
          py::arg("theta"),
          "Resistance to sliding along θ [rad]: N_W((cos θ, sin θ)) (= mu; tribometer_law.csv's support_mu).")
      .def(
          "radial_mu",
          [](const FrictionLaw& l, const py::object& theta) { return along_angles(l, theta, "radial_mu", radial_mu); },
          py::arg("theta"),
          "The friction set's boundary in direction θ [rad]: max{s : s·(cos θ, sin θ) ∈ W}, the largest\n"
          "friction force per unit normal force that points along θ — the tribometer's μ(θ) in |F_t| = μ(θ)·P\n"
          "(tribometer_law.csv's radial_mu, tribometer_polar.csv's law_mu). Equals mu(θ) only where the\n"
          "boundary's normal is along θ (isotropic laws, the axes of an ellipse).")
      .def(
          "support", [](const FrictionLaw& l, const py::object& u) { return l.support(tangential(u)); }, py::arg("u"),
          "Support function N_W(u) = max_{w∈W} ⟨w, u⟩: the dissipation per unit normal force for a\n"
          "slip u (a float in 2D, two floats in 3D; units of u).")
      .def(
          "exposed_point",
          [](const FrictionLaw& l, const py::object& u) { return to_numpy(Eigen::VectorXd(l.exposed_point(tangential(u)))); },
          py::arg("u"), "An element of argmax_{w∈W} ⟨w, u⟩ = ∂N_W(u) (for u = 0: the point 0).")
      .def(
          "project",
          [](const FrictionLaw& l, const py::object& q, double s) {
            if (!(s >= 0.0)) throw InvalidInput(fmt::format("project: s = {}; expected s >= 0", s));
            return to_numpy(Eigen::VectorXd(l.project(tangential(q), s)));
          },
          py::arg("q"), py::arg("s") = 1.0,
          "Euclidean projection of the friction force q onto s·W (s >= 0, e.g. the normal force λ [N]).")
      .def("describe", &FrictionLaw::describe, "One line, e.g. 'polygon(n=4, mu=[0.4, 0.2, 0.4, 0.2])'.")
      .def("__repr__", [](const FrictionLaw& l) { return "<frictopt.FrictionLaw " + l.describe() + ">"; });
}

}  // namespace frictopt::python
