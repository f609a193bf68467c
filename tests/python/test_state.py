# SPDX-License-Identifier: MIT
"""Body.solve: array shapes, SI units, views without copies, mechanics checks."""
from __future__ import annotations

import gc

import numpy as np
import pytest

import frictopt


@pytest.fixture(scope="module")
def solved(coarse_case: frictopt.Case):
    body = frictopt.Body(coarse_case)
    return body, body.solve()


def test_shapes(solved) -> None:
    body, s = solved
    n, p = 9 * 9 * 5, body.num_contact_nodes
    assert p == 81
    assert s.positions.shape == (n, 3) and s.displacement.shape == (n, 3)
    assert s.stress.shape == (n, 6) and s.von_mises.shape == (n,)
    assert s.element_stress.shape == (8 * 8 * 4, 6)
    assert s.normal_force.shape == (p,) and s.pressure.shape == (p,)
    assert s.friction_force.shape == (p, 2) and s.tangential_force.shape == (p, 2)
    assert s.tangential_traction.shape == (p, 2) and s.slip.shape == (p, 2)
    assert s.contact_status.shape == (p,) and s.contact_status.dtype == np.int8
    assert set(np.unique(s.contact_status)) <= {0, 1, 2}
    assert body.contact_coordinates.shape == (p, 2) and body.tributary_areas.shape == (p,)


def test_the_module_calls_openblas(solved) -> None:
    # The extension module's CHOLMOD calls OpenBLAS, not the ATLAS Debian's Ceres also needs
    # (docs/benchmarks.md, "Which BLAS"); the summary names the implementation and its file.
    _, s = solved
    assert s.summary.blas.startswith("OpenBLAS"), s.summary.blas
    library = s.summary.blas.split("(dgemm_ from ", 1)[1]
    assert "openblas" in library and "atlas" not in library, s.summary.blas


def test_units_and_mechanics(solved, coarse_case: frictopt.Case) -> None:
    body, s = solved
    assert s.converged, s.message
    # The plate moves 1.2 mm down: displacements are O(1e-3) m; the top face follows it exactly.
    top = np.isclose(s.positions[:, 2], s.positions[:, 2].max())
    np.testing.assert_allclose(s.displacement[top], np.tile([1.0e-4, 0.0, -1.2e-3], (top.sum(), 1)), atol=1e-15)
    # Tributary areas tile the 1 m × 1 m contact face; pressure = λ / a in Pa.
    assert body.tributary_areas.sum() == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(s.pressure, s.normal_force / body.tributary_areas, rtol=1e-15)
    np.testing.assert_allclose(s.tangential_traction, s.tangential_force / body.tributary_areas[:, None], rtol=1e-15)
    np.testing.assert_array_equal(s.tangential_force, -s.friction_force)
    assert s.summary.contact.total_normal_force == pytest.approx(s.normal_force.sum(), rel=1e-15)
    # Coulomb: q ∈ λ·W (projection leaves it), slipping nodes at the limit with q opposing... the
    # dissipation λ N_W(u_t) = ⟨q, u_t⟩ (spec: maximum dissipation).
    law = coarse_case.friction_law
    for i in range(body.num_contact_nodes):
        lam, q = s.normal_force[i], s.friction_force[i]
        np.testing.assert_allclose(law.project(q, lam), q, atol=1e-9 * s.normal_force.max())
        if s.contact_status[i] == frictopt.STATUS_SLIP:
            u = s.slip[i]
            assert lam * law.support(u) == pytest.approx(q @ u, rel=1e-6)
        if s.contact_status[i] == frictopt.STATUS_SEPARATED:
            assert lam <= 1e-6 * s.normal_force.max()
    assert 0.0 < s.stick_fraction < 1.0
    assert s.strain_energy > 0.0 and s.volume == pytest.approx(0.499, rel=1e-3)


def test_large_arrays_are_read_only_views_that_keep_the_state_alive(coarse_case: frictopt.Case) -> None:
    body = frictopt.Body(coarse_case)
    s = body.solve()
    u = s.displacement
    assert not u.flags.owndata and u.base is s and not u.flags.writeable
    with pytest.raises(ValueError):
        u[0, 0] = 1.0
    # Every access is a view of the same C++ memory (no copy per access).
    assert np.shares_memory(s.displacement, u)
    lam = s.normal_force
    assert lam.base is s and lam.strides == (3 * 8,)  # λ_i inside the interleaved z = (q_1, λ_1, ...)
    expected, u_expected = lam.copy(), u.copy()
    del s
    gc.collect()
    body.solve(body.initial_design * 1.01)  # a new state; the old one lives on through its views
    np.testing.assert_array_equal(lam, expected)
    np.testing.assert_array_equal(u, u_expected)


def test_design_argument_and_errors(coarse_case: frictopt.Case) -> None:
    body = frictopt.Body(coarse_case)
    s = body.solve(body.initial_design)
    np.testing.assert_array_equal(s.alpha, body.initial_design)
    with pytest.raises(ValueError, match="alpha has 3 entries; expected 16"):
        body.solve([0.0, 0.0, 0.0])
    assert body.design_violation() == ""
    assert body.design_violation(np.full(16, 1.0)) != ""  # 1 m > the upper bound 5 mm
    # A design outside Υ is solved, but not silently; a complex one is refused (numpy would drop
    # the imaginary part).
    with pytest.warns(RuntimeWarning, match="alpha is outside the admissible set"):
        body.solve(np.full(16, -1.0e-3))
    with pytest.raises(ValueError, match="alpha: complex values; expected 16 real numbers"):
        body.solve(np.asarray(body.initial_design, dtype=complex))
    with pytest.raises(ValueError, match="complex values"):
        frictopt.Oracle(coarse_case).evaluate(np.asarray(body.initial_design, dtype=complex))


def test_numerical_failure_is_a_status_not_an_exception(coarse_case: frictopt.Case) -> None:
    case = coarse_case.with_overrides(solver={"coulomb": {"max_iterations": 1}, "qp": {"max_iterations": 1}})
    s = frictopt.Body(case).solve()
    assert not s.converged
    assert s.status in ("max_iterations", "numerical_failure", "stalled")
    assert s.summary.status == s.status and s.message


def test_2d_case_shapes(root) -> None:
    case = frictopt.load_case(root / "cases2d" / "ex521-target-pressure" / "case.toml")
    body = frictopt.Body(case)
    s = body.solve()
    assert s.converged
    assert s.displacement.shape[1] == 2 and s.stress.shape[1] == 6
    assert s.friction_force.shape == (body.num_contact_nodes, 1) and s.slip.shape == (body.num_contact_nodes, 1)


def test_repr_reads_well(solved) -> None:
    body, s = solved
    assert repr(body).startswith("<frictopt.Body 'punch-anisotropic': 3D")
    assert "contact nodes (stick" in repr(s)
    assert "status='converged'" in repr(s.summary)


def test_tetrahedra_solve_and_check_gradient(coarse_case: frictopt.Case) -> None:
    # [mesh] element = "tet4" (docs/meshes.md, "Tetrahedra and triangles"): the same grid split into
    # 6 tetrahedra per cell, the same nodes and contact nodes; ξ against central differences.
    case = coarse_case.with_overrides(mesh={"element": "tet4"})
    body = frictopt.Body(case)
    assert body.element == "tet4" and body.num_elements == 8 * 8 * 4 * 6
    assert frictopt.Body(coarse_case).element == "hex8"
    s = body.solve()
    assert s.converged
    assert s.element_stress.shape == (8 * 8 * 4 * 6, 6) and s.positions.shape == (9 * 9 * 5, 3)
    assert body.num_contact_nodes == 81 and abs(body.tributary_areas.sum() - 1.0) < 1e-12
    assert "1536 tet4 cells" in repr(body)
    r = frictopt.check_gradient(case)
    assert r.ok and set(r.verdicts) <= {"match", "kink"}, r.verdicts
