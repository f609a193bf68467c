# SPDX-License-Identifier: MIT
"""FrictionLaw: μ(θ) as the support function, vertices, projection onto s·W."""
from __future__ import annotations

import numpy as np
import pytest

import frictopt

THETA = np.linspace(0.0, 2.0 * np.pi, 181)


def test_disc_and_regular_polygon() -> None:
    disc = frictopt.FrictionLaw.disc(0.3)
    np.testing.assert_allclose(disc.mu(THETA), 0.3, rtol=1e-15)
    assert disc.vertices.shape == (0, 2)
    square = frictopt.FrictionLaw.regular_polygon(0.5, 4)
    # Vertices at π/4 + kπ/2 with |w| = μ: μ(θ) = μ·max_j cos(φ_j − θ).
    phi = np.pi * (2 * np.arange(1, 5) - 1) / 4
    expected = 0.5 * np.max(np.cos(phi[None, :] - THETA[:, None]), axis=1)
    np.testing.assert_allclose(square.mu(THETA), expected, rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(square.vertices, axis=1), 0.5, rtol=1e-14)


def test_anisotropic_polygon_vertices_and_mu() -> None:
    law = frictopt.FrictionLaw.polygon([0.4, 0.2, 0.4, 0.2])
    assert law.kind == "polygon" and law.dim == 3 and law.is_polygonal
    np.testing.assert_allclose(np.linalg.norm(law.vertices, axis=1), [0.4, 0.2, 0.4, 0.2], rtol=1e-14)
    assert law.mu(np.pi / 4) == pytest.approx(0.4, rel=1e-14)   # along a vertex: its coefficient
    assert law.mu(3 * np.pi / 4) == pytest.approx(0.2, rel=1e-14)
    assert law.max_coefficient == pytest.approx(0.4)
    # μ(θ) is the support function along (cos θ, sin θ); scalar and array calls agree.
    for t in THETA[::20]:
        assert law.mu(t) == pytest.approx(law.support([np.cos(t), np.sin(t)]), rel=1e-15)
    assert law.mu(THETA.reshape(-1, 1)).shape == (THETA.size, 1)
    assert law.edge_normals.shape == (4, 2) and law.edge_heights.shape == (4,)


def test_ellipse_and_interval() -> None:
    e = frictopt.FrictionLaw.ellipse(0.5, 0.25)
    # Support function of an ellipse: sqrt((μx cos θ)² + (μy sin θ)²).
    np.testing.assert_allclose(e.mu(THETA), np.hypot(0.5 * np.cos(THETA), 0.25 * np.sin(THETA)), rtol=1e-12)
    np.testing.assert_allclose(e.semi_axes, [0.5, 0.25])
    i = frictopt.FrictionLaw.interval(0.1, 0.3)
    assert i.dim == 2
    assert i.mu(0.0) == pytest.approx(0.3) and i.mu(np.pi) == pytest.approx(0.1)
    assert i.support(2.0) == pytest.approx(0.6)


def test_projection_is_onto_s_times_w() -> None:
    law = frictopt.FrictionLaw.polygon([0.4, 0.2, 0.4, 0.2])
    rng = np.random.default_rng(3)
    for q in rng.normal(size=(50, 2)):
        p = law.project(q, 2.0)
        # Inside 2W: every edge constraint ⟨e_j, p⟩ <= 2 h_j holds; projecting again changes nothing.
        assert np.all(law.edge_normals @ p <= 2.0 * law.edge_heights + 1e-12)
        np.testing.assert_allclose(law.project(p, 2.0), p, atol=1e-15)
        # Optimality: ⟨q − p, w − p⟩ <= 0 for the vertices w of 2W.
        assert np.all((2.0 * law.vertices - p) @ (q - p) <= 1e-12)
    np.testing.assert_allclose(law.exposed_point([1.0, 1.0]), law.vertices[0], rtol=1e-14)


def test_invalid_laws_raise_value_error() -> None:
    with pytest.raises(ValueError, match="mu"):
        frictopt.FrictionLaw.disc(-0.1)
    with pytest.raises(ValueError, match="vertex"):
        frictopt.FrictionLaw.polygon([0.4, 0.01, 0.4, 0.01, 0.4, 0.01])
    with pytest.raises(ValueError, match="s >= 0"):
        frictopt.FrictionLaw.disc(0.3).project([1.0, 0.0], -1.0)
    assert "polygon(n=4" in repr(frictopt.FrictionLaw.polygon([0.4, 0.2, 0.4, 0.2]))
