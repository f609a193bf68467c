# SPDX-License-Identifier: MIT
"""Oracle Θ(α) and its subgradient, check_gradient, certify, FCLIB export."""
from __future__ import annotations

import json
import pathlib

import numpy as np
import pytest

import frictopt


@pytest.fixture(scope="module")
def oracle(coarse_case: frictopt.Case) -> frictopt.Oracle:
    return frictopt.Oracle(coarse_case)


def test_evaluate_and_call(oracle: frictopt.Oracle, coarse_case: frictopt.Case) -> None:
    e = oracle.evaluate()
    assert e.ok, e.message
    assert e.value > 0.0 and e.subgradient.shape == (16,)
    theta, xi = oracle(coarse_case.initial_design)
    assert theta == e.value
    np.testing.assert_array_equal(xi, e.subgradient)
    assert oracle.cost == "target_pressure"  # the case file's [cost] kind, not the functional's own name
    assert len(oracle.friction_parameters) == e.friction_gradient.size == 4
    assert "Θ =" in repr(e) and "frictopt.Oracle" in repr(oracle)


def test_subgradient_matches_a_directional_difference(oracle: frictopt.Oracle, coarse_case: frictopt.Case) -> None:
    alpha = coarse_case.initial_design
    e = oracle.evaluate(alpha)
    direction = np.random.default_rng(1).normal(size=alpha.size)
    h = 1e-8
    forward = oracle.evaluate(alpha + h * direction, with_subgradient=False).value
    backward = oracle.evaluate(alpha - h * direction, with_subgradient=False).value
    if e.weak_nodes == 0:  # smooth here: the adjoint ξ is the gradient
        assert (forward - backward) / (2 * h) == pytest.approx(e.subgradient @ direction, rel=1e-5)


def test_oracle_needs_contact_and_cost(coarse_case: frictopt.Case) -> None:
    with pytest.raises(ValueError, match="cost"):
        frictopt.Oracle(coarse_case.with_overrides(cost=None))
    with pytest.raises(ValueError, match="alpha has 2 entries"):
        frictopt.Oracle(coarse_case).evaluate([1.0, 2.0])


def test_check_gradient(coarse_case: frictopt.Case) -> None:
    r = frictopt.check_gradient(coarse_case)
    assert r.ok and r.subgradient.shape == r.finite_difference.shape == (16,)
    if r.weak_nodes == 0:
        assert r.max_relative_error < 1e-4
    assert set(r.friction_gradient) == {f"mu_vertices[{j}]" for j in range(4)}
    # Steps relative to the width of each variable's bounds (C0 for the control heights), not to
    # max|α| (a flat start α⁰ = 0 once gave h = 1e-16 m).
    c0 = coarse_case.to_dict()["design"]["upper_bound"]
    assert r.step == pytest.approx(1e-6 * c0)
    assert len(r.verdicts) == 16 and set(r.verdicts) <= {"match", "kink", "MISMATCH"}
    assert np.all(np.isfinite(r.forward_difference)) and np.all(np.isfinite(r.backward_difference))
    assert len(r.piece_changes) == 16 and not r.warnings, r.warnings


def test_certify_at_the_initial_design(coarse_case: frictopt.Case) -> None:
    c = frictopt.certify(coarse_case, cap=64)
    assert c.status == "converged", c.message
    assert c.command == "certify" and c.value > 0.0
    assert c.cardinality_L >= 1 and len(c.pieces) >= 1
    assert c.clarke.distance >= 0.0 and c.clarke.relative_distance <= 1.0 + 1e-12
    # Far from optimal: the initial dish is not stationary.
    assert not c.clarke.stationary
    assert "Clarke" in c.report or "δ" in c.report
    assert isinstance(c.mf1.full_row_rank, bool)
    assert json.loads(c.to_json())["status"] == "converged"


def test_certify_with_a_sampled_certificate(coarse_case: frictopt.Case) -> None:
    # The sampled (Goldstein) certificate adds ξ at designs within the radius: its distance cannot
    # exceed the exact one (its generators contain those at the point).
    c = frictopt.certify(coarse_case, cap=64, sample_radius=1e-6, samples=4)
    assert c.status == "converged", c.message
    g = c.goldstein
    assert g.evaluated == 4 and g.skipped == 0
    assert 0.0 < g.largest_step <= 1e-6 * (1 + 1e-12)
    assert g.distance <= c.clarke.distance * (1 + 1e-6) + 1e-12 * c.scale_max_xi_norm
    assert "sampled certificate" in c.report
    with pytest.raises(ValueError, match="sample_radius = -1; expected a finite radius >= 0"):
        frictopt.certify(coarse_case, sample_radius=-1.0)


def test_export_fclib(root, tmp_path) -> None:
    case = frictopt.load_case(root / "cases3d" / "punch" / "case.toml").with_overrides(mesh={"cells": [6, 6, 3]})
    body = frictopt.Body(case)
    state = body.solve()
    info = body.export_fclib(tmp_path / "punch.hdf5", state)
    assert (tmp_path / "punch.hdf5").stat().st_size > 0
    assert info.spacedim == 3 and info.num_contacts == body.num_contact_nodes
    assert info.force_unit == 1.0 and info.length_unit == 1.0
    with pytest.raises(ValueError, match="not solved on this body"):
        frictopt.Body(case).export_fclib(tmp_path / "x.hdf5", state)


def test_export_fclib_rejects_anisotropic_laws(coarse_case: frictopt.Case, tmp_path) -> None:
    body = frictopt.Body(coarse_case)
    state = body.solve()
    with pytest.raises(ValueError, match="isotropic"):
        body.export_fclib(tmp_path / "x.hdf5", state)
    assert not (tmp_path / "x.hdf5").exists()


def test_friction_orientation_case_uses_x_with_the_orientation_last(root: pathlib.Path) -> None:
    # [design] friction_orientation: the optimizer's x = (α, s); Case, Body and Oracle agree on
    # its size, ξ has the ∂Θ/∂s entry last, and check_gradient checks all of x (it refused the
    # 16-entry α before).
    case = frictopt.load_case(str(root / "cases3d" / "punch-orientation" / "case.toml"))
    assert case.num_design_variables == 17 and case.initial_design.shape == (17,)
    oracle = frictopt.Oracle(case)
    assert oracle.num_design_variables == 17
    np.testing.assert_array_equal(oracle.initial_design, case.initial_design)
    e = oracle.evaluate()
    assert e.ok, e.message
    assert e.subgradient.shape == (17,) and e.subgradient[16] != 0.0
    with pytest.raises(ValueError, match="expected 17"):
        oracle.evaluate(case.initial_design[:16])
    summary = frictopt.check_gradient(case)
    assert summary["value"] == pytest.approx(e.value, rel=1e-6)
    assert len(summary["subgradient"]) == 17
