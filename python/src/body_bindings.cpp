// SPDX-License-Identifier: MIT
// frictopt.Body and frictopt.State: study::ElasticBody and its BodyState with numpy views of
// the large arrays (no copies; the State is the views' base object), plus VTK and FCLIB export.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/io/fclib_export.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"

namespace frictopt::python {

io::JsonValue solve_summary_json(const Case& source, const study::ElasticBody& body, const study::BodyState& state) {
  return io::solve_summary(source.description.origin, body, state);  // the CLI's summary.json
}

namespace {

const study::ContactResult& contact_of(const State& s) {
  if (!s.state->contact)
    throw InvalidInput("this state has no contact result (the case has no [contact], or the elasticity solve failed: " +
                       s.state->summary.message + ")");
  return *s.state->contact;
}

// A per-contact-node (p, dim−1) array of `sign`·(component k of block i of v) / scale_i.
py::array tangential_rows(const Eigen::VectorXd& v, int dim, double sign, const Eigen::VectorXd* scale) {
  const Eigen::Index p = v.size() / dim;
  Eigen::MatrixXd out(p, dim - 1);
  for (Eigen::Index i = 0; i < p; ++i)
    for (int k = 0; k < dim - 1; ++k) out(i, k) = sign * v(dim * i + k) / (scale ? (*scale)(i) : 1.0);
  return to_numpy(out);
}

void check_owner(const Body& b, const State& s) {
  if (s.body.get() != &b) throw InvalidInput("the state was not solved on this body");
}

}  // namespace

void bind_body(py::module_& m) {
  py::class_<State, std::shared_ptr<State>>(m, "State", R"doc(
The state of a body at one design, from ``Body.solve``. SI units: m, N, Pa, J.

The large arrays (positions, displacement, stresses, normal forces) are read-only numpy views of
the C++ result, without copies; the State stays alive as long as any view does. Per contact
node (p nodes, in the order of ``Body.contact_coordinates``) the contact arrays give the
normal force λ [N], the friction force q = −τ and tangential force τ [N], pressure and
tangential traction [Pa] (force / tributary area), the slip u_t [m] and the status
(0 separated, 1 stick, 2 slip). In 2D forces are per metre of thickness and tangential arrays
have one column. A failed solve is reported by ``status``/``message``, not raised.
)doc")
      .def_property_readonly("status", [](const State& s) { return std::string(to_string(s.state->summary.status)); },
                             "'converged', or the reason the state solve failed ('numerical_failure', ...).")
      .def_property_readonly("message", [](const State& s) { return s.state->summary.message; }, "The solver's message.")
      .def_property_readonly("converged", [](const State& s) { return s.state->summary.status == Status::kConverged; },
                             "True when elasticity and contact converged.")
      .def_property_readonly(
          "summary",
          [](const State& s) { return to_python(solve_summary_json(*s.body->source, *s.body->body, *s.state)); },
          "A frictopt.Summary with the fields (and values) of the CLI's ``frictopt solve`` summary.json.")
      .def_property_readonly("alpha", [](const State& s) { return to_numpy(s.state->alpha); }, "The design α [m].")
      .def_property_readonly("strain_energy", [](const State& s) { return s.state->strain_energy; },
                             "½ uᵀAu [J] (2D: J per metre of thickness).")
      .def_property_readonly("external_work", [](const State& s) { return s.state->external_work; },
                             "Work of the loads lᵀu [J].")
      .def_property_readonly("volume", [](const State& s) { return s.state->volume; }, "Volume of Ω(α) [m³; 2D: m²].")
      .def_property_readonly(
          "positions",
          [](py::object self) {
            const auto& X = self.cast<const State&>().state->positions;
            return readonly_view(X.data(), {X.rows(), X.cols()}, {1, X.rows()}, self);
          },
          "Node positions X(α) of the undeformed design, (num_nodes, dim) [m] (view).")
      .def_property_readonly(
          "displacement",
          [](py::object self) {
            const auto& s = self.cast<const State&>();
            const auto dim = s.state->positions.cols();
            const auto& u = s.state->displacement;
            return readonly_view(u.data(), {u.size() / dim, dim}, {dim, 1}, self);
          },
          "Displacement u per node, (num_nodes, dim) [m] (view).")
      .def_property_readonly(
          "stress",
          [](py::object self) {
            const auto& S = self.cast<const State&>().state->stress.nodal;
            return readonly_view(S.data(), {S.rows(), S.cols()}, {1, S.rows()}, self);
          },
          "Nodal Cauchy stress (xx, yy, zz, xy, yz, xz), (num_nodes, 6) [Pa] (view; element averages).")
      .def_property_readonly(
          "element_stress",
          [](py::object self) {
            const auto& S = self.cast<const State&>().state->stress.element;
            return readonly_view(S.data(), {S.rows(), S.cols()}, {1, S.rows()}, self);
          },
          "Stress at the element centres, (num_elements, 6) [Pa] (view).")
      .def_property_readonly(
          "von_mises",
          [](py::object self) {
            const auto& v = self.cast<const State&>().state->stress.nodal_von_mises;
            return readonly_view(v.data(), {v.size()}, {1}, self);
          },
          "Nodal von Mises stress, (num_nodes,) [Pa] (view).")
      .def_property_readonly("has_contact", [](const State& s) { return s.state->contact.has_value(); },
                             "True when the state has a contact result.")
      .def_property_readonly(
          "normal_force",
          [](py::object self) {
            const auto& c = contact_of(self.cast<const State&>());
            const int dim = c.state.dim;
            return readonly_view(c.state.z.data() + dim - 1, {c.state.num_nodes()}, {dim}, self);
          },
          "Normal force λ per contact node, (p,) [N] (view).")
      .def_property_readonly(
          "friction_force",
          [](py::object self) {
            const auto& c = contact_of(self.cast<const State&>());
            const int dim = c.state.dim;
            return readonly_view(c.state.z.data(), {c.state.num_nodes(), dim - 1}, {dim, 1}, self);
          },
          "Friction resistance q = −τ per contact node, (p, dim−1) [N] (view; q ∈ λ·W).")
      .def_property_readonly(
          "tangential_force",
          [](const State& s) {
            const auto& c = contact_of(s);
            return tangential_rows(c.state.z, c.state.dim, -1.0, nullptr);
          },
          "Tangential force τ = −q the foundation exerts on the body, (p, dim−1) [N].")
      .def_property_readonly(
          "pressure",
          [](const State& s) {
            const auto& c = contact_of(s);
            return to_numpy(Eigen::VectorXd(c.state.normal_forces().cwiseQuotient(s.body->tributary_areas)));
          },
          "Contact pressure λ / a per contact node, (p,) [Pa] (a the tributary area).")
      .def_property_readonly(
          "tangential_traction",
          [](const State& s) {
            const auto& c = contact_of(s);
            return tangential_rows(c.state.z, c.state.dim, -1.0, &s.body->tributary_areas);
          },
          "Tangential traction τ / a per contact node, (p, dim−1) [Pa].")
      .def_property_readonly(
          "slip",
          [](const State& s) {
            const auto& c = contact_of(s);
            return tangential_rows(c.state.gradient, c.state.dim, -1.0, nullptr);
          },
          "Tangential displacement (slip) u_t per contact node, (p, dim−1) [m].")
      .def_property_readonly(
          "normal_gap",
          [](py::object self) {
            const auto& c = contact_of(self.cast<const State&>());
            const int dim = c.state.dim;
            return readonly_view(c.state.gradient.data() + dim - 1, {c.state.num_nodes()}, {dim}, self);
          },
          "Gap after deformation u_ν + g per contact node, (p,) [m] (view; 0 where in contact).")
      .def_property_readonly(
          "initial_gap",
          [](py::object self) {
            const auto& g = contact_of(self.cast<const State&>()).gaps;
            return readonly_view(g.data(), {g.size()}, {1}, self);
          },
          "Initial gap g = B̃α per contact node, (p,) [m] (view).")
      .def_property_readonly(
          "contact_status",
          [](const State& s) {
            const auto& c = contact_of(s);
            py::array_t<std::int8_t> out(c.state.num_nodes());
            auto r = out.mutable_unchecked<1>();
            for (Eigen::Index i = 0; i < c.state.num_nodes(); ++i)
              r(i) = static_cast<std::int8_t>(c.state.nodes[static_cast<std::size_t>(i)].status);
            return out;
          },
          "Status per contact node, (p,) int8: 0 separated, 1 stick, 2 slip (as VTK's contact_status).")
      .def_property_readonly(
          "stick_fraction",
          [](const State& s) {
            const auto& c = contact_of(s);
            double stick = 0.0, total = 0.0;
            for (Eigen::Index i = 0; i < c.state.num_nodes(); ++i) {
              total += s.body->tributary_areas(i);
              if (c.state.is_stick(i)) stick += s.body->tributary_areas(i);
            }
            return stick / total;
          },
          "Area fraction of Γ_c that sticks (tributary-area weighted) [-].")
      .def_property_readonly(
          "contact_summary",
          [](const State& s) {
            const io::JsonValue j = solve_summary_json(*s.body->source, *s.body->body, *s.state);
            return to_python(j.at("contact"));
          },
          "The contact solver's summary (the 'contact' table of summary.json).")
      .def("__repr__", [](const State& s) {
        const auto& st = *s.state;
        std::string contact;
        if (st.contact) {
          int counts[3] = {0, 0, 0};
          for (const auto& n : st.contact->state.nodes) ++counts[static_cast<int>(n.status)];
          contact = fmt::format(", {} contact nodes (stick {}, slip {}, separated {}), total normal force {:.6g} N",
                                st.contact->state.num_nodes(), counts[1], counts[2], counts[0],
                                st.contact->state.normal_forces().sum());
        }
        return fmt::format("<frictopt.State {}: {} nodes{}, strain energy {:.6g} J>", to_string(st.summary.status),
                           st.positions.rows(), contact, st.strain_energy);
      });

  py::class_<Body, std::shared_ptr<Body>>(m, "Body", R"doc(
One elastic body of a case on its fixed mesh (study::ElasticBody): solves the state — linear
elasticity and, with a foundation, unilateral contact with Coulomb friction — for any design α.

The mesh, the sparsity pattern and the symbolic factorization are built once and reused;
each solve warm-starts the contact solver from the previous one. ``solve`` releases the GIL.
SI units: α in m, forces in N, stresses in Pa.

Example::

    body = frictopt.Body(frictopt.load_case("cases3d/punch-anisotropic/case.toml"))
    state = body.solve()                 # at the initial design α⁰
    state.pressure.max(), state.stick_fraction
)doc")
      .def(py::init([](std::shared_ptr<const Case> source) {
             auto b = std::make_shared<Body>();
             b->source = source;
             {
               py::gil_scoped_release release;
               b->body = std::make_unique<study::ElasticBody>(source->description.body);
             }
             if (b->body->contact_boundary()) b->tributary_areas = io::contact_tributary_areas(*b->body);
             return b;
           }),
           py::arg("case"), "Builds the mesh and the finite-element problem of `case` (ValueError on bad input).")
      .def(
          "solve",
          [](std::shared_ptr<Body> self, const py::object& alpha) {
            const Eigen::VectorXd a =
                design_from_python(alpha, self->body->initial_design(), "alpha");
            if (!alpha.is_none()) warn_if_outside(*self->body, a, "alpha");
            const std::string label = alpha.is_none() ? "initial design" : "design";
            auto state = std::make_shared<State>();
            state->body = self;
            {
              py::gil_scoped_release release;
              const std::lock_guard lock(self->mutex);
              state->state = std::make_shared<const study::BodyState>(self->body->solve(a, label));
            }
            return state;
          },
          py::arg("alpha") = py::none(),
          "Solves the state at design α (control heights [m]; default the initial design α⁰) and\n"
          "returns a State. Raises ValueError when α has the wrong size or inverts an element; a\n"
          "failed factorization or contact solve is the State's status.")
      .def_property_readonly("name", [](const Body& b) { return b.body->definition().name; }, "Output base name.")
      .def_property_readonly("dim", [](const Body& b) { return b.body->definition().shape.dim(); }, "2 or 3.")
      .def_property_readonly("num_unknowns", [](const Body& b) { return b.body->elasticity().dofs().num_free(); },
                             "Free displacement unknowns of the finite-element problem.")
      .def_property_readonly("element", [](const Body& b) { return std::string(mesh::to_string(b.body->mesh().element_kind())); },
                             "The cells: 'hex8', 'tet4' (3D), 'quad4', 'tri3' (2D) ([mesh] element).")
      .def_property_readonly("num_elements", [](const Body& b) { return b.body->mesh().num_elements(); },
                             "Number of cells of the mesh.")
      .def_property_readonly("num_design_variables",
                             [](const Body& b) { return b.body->num_design_variables(); },
                             "Number of control heights α.")
      .def_property_readonly("num_contact_nodes",
                             [](const Body& b) { return b.body->contact_boundary() ? b.body->contact_boundary()->num_nodes() : 0; },
                             "Number p of contact nodes on Γ_c (0 without contact).")
      .def_property_readonly("initial_design", [](const Body& b) { return to_numpy(b.body->initial_design()); },
                             "α⁰ [m].")
      .def_property_readonly(
          "friction_law",
          [](const Body& b) -> py::object {
            if (!b.body->definition().contact) return py::none();
            return py::cast(b.body->definition().contact->law);
          },
          "The friction law (FrictionLaw) or None.")
      .def_property_readonly(
          "contact_coordinates",
          [](const Body& b) -> py::object {
            if (!b.body->contact_boundary()) return py::none();
            return to_numpy(b.body->contact_boundary()->plane_coordinates());
          },
          "In-plane coordinates x' of the contact nodes, (p, dim−1) [m].")
      .def_property_readonly(
          "contact_nodes",
          [](const Body& b) {
            py::array_t<std::int64_t> out(b.body->contact_boundary() ? b.body->contact_boundary()->num_nodes() : 0);
            if (b.body->contact_boundary()) {
              const auto& nodes = b.body->contact_boundary()->nodes();
              std::copy(nodes.begin(), nodes.end(), out.mutable_data());
            }
            return out;
          },
          "Mesh node index of each contact node, (p,): rows of State.positions / displacement, points of the VTK file.")
      .def_property_readonly("tributary_areas", [](const Body& b) { return to_numpy(b.tributary_areas); },
                             "Area of Γ_c attributed to each contact node, (p,) [m²; 2D: m].")
      .def(
          "design_violation",
          [](const Body& b, const py::object& alpha, double tolerance) {
            const Eigen::VectorXd a = design_from_python(alpha, b.body->initial_design(), "alpha");
            return b.body->admissible_set().describe_violation(a, tolerance);
          },
          py::arg("alpha") = py::none(), py::arg("tolerance") = 1e-9,
          "Which constraint of the admissible set Υ α violates by more than `tolerance` [m]; '' when admissible.")
      .def(
          "write_vtk",
          [](const Body& b, const std::filesystem::path& path, const State& s) {
            check_owner(b, s);
            io::write_state_vtu(path, *b.body, *s.state);
          },
          py::arg("path"), py::arg("state"),
          "Writes the state as a VTK unstructured grid (.vtu): displacement [m], stress and von Mises [Pa],\n"
          "and on Γ_c contact_pressure and contact_traction [Pa], slip and contact_gap [m], contact_status.")
      .def(
          "export_fclib",
          [](const Body& b, const std::filesystem::path& path, const State& s, bool normalize_units,
             bool include_solution) {
            check_owner(b, s);
            io::FclibExportOptions options;
            options.case_name = b.source->description.origin;
            options.normalize_units = normalize_units;
            options.include_solution = include_solution;
            const io::FclibLocalProblem p = io::export_fclib_local(path, *b.body, *s.state, options);
            io::JsonValue j = io::JsonValue::object();
            j["path"] = path.string();
            j["spacedim"] = p.spacedim;
            j["num_contacts"] = static_cast<std::int64_t>(p.num_contacts());
            j["mu"] = p.mu;
            j["force_unit"] = p.force_unit;
            j["length_unit"] = p.length_unit;
            j["solution_is_exact"] = p.solution_is_exact;
            j["natural_map_residual"] = p.r.size() ? io::fclib_natural_map_residual(p, p.r) : kNaN;
            j["title"] = p.title;
            return to_python(j);
          },
          py::arg("path"), py::arg("state"), py::arg("normalize_units") = false, py::arg("include_solution") = true,
          "Writes the contact problem at `state` (the body's last solve) in FCLIB's local format (HDF5)\n"
          "and returns a Summary (spacedim, num_contacts, mu, force_unit [N], length_unit [m],\n"
          "solution_is_exact, natural_map_residual). Isotropic laws only (ValueError otherwise).")
      .def("__repr__", [](const Body& b) {
        const auto& d = b.body->definition();
        return fmt::format("<frictopt.Body '{}': {}D, {} {} cells, {} unknowns, {} contact nodes, {} design variables>",
                           d.name, d.shape.dim(), b.body->mesh().num_elements(),
                           mesh::to_string(b.body->mesh().element_kind()), b.body->elasticity().dofs().num_free(),
                           b.body->contact_boundary() ? b.body->contact_boundary()->num_nodes() : 0,
                           b.body->num_design_variables());
      });
}

}  // namespace frictopt::python
