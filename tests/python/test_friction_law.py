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


def test_the_two_meanings_of_mu_theta() -> None:
    # An ellipse with μ 0.25 along the lay and 0.4 across: at 45° the resistance to sliding along
    # θ (support function, mu / support_mu) and the friction set's boundary in direction θ (radial
    # function, radial_mu: the tribometer's μ(θ) in |F_t| = μ(θ)·P) are 11 % apart.
    law = frictopt.FrictionLaw.ellipse(0.25, 0.4)
    t = np.pi / 4
    assert law.mu(t) == law.support_mu(t) == pytest.approx(np.sqrt((0.25**2 + 0.4**2) / 2), rel=1e-14)
    assert law.radial_mu(t) == pytest.approx(1.0 / np.sqrt(0.5 / 0.25**2 + 0.5 / 0.4**2), rel=1e-12)
    assert law.mu(t) / law.radial_mu(t) == pytest.approx(1.1125, rel=1e-12)
    # Along the axes the two agree; the radial point lies on W's boundary.
    np.testing.assert_allclose(law.radial_mu(np.array([0.0, np.pi / 2])), [0.25, 0.4], rtol=1e-12)
    np.testing.assert_allclose(law.support_mu(np.array([0.0, np.pi / 2])), [0.25, 0.4], rtol=1e-12)
    point = law.radial_mu(t) * np.array([np.cos(t), np.sin(t)])
    assert (point[0] / 0.25) ** 2 + (point[1] / 0.4) ** 2 == pytest.approx(1.0, rel=1e-12)
    # Isotropic: one μ.
    disc = frictopt.FrictionLaw.disc(0.3)
    np.testing.assert_allclose(disc.radial_mu(THETA), disc.mu(THETA), rtol=1e-13)
    # 2D interval [−μ₋, μ₊]: the two ends.
    i = frictopt.FrictionLaw.interval(0.1, 0.3)
    assert i.radial_mu(0.0) == pytest.approx(0.3) and i.radial_mu(np.pi) == pytest.approx(0.1)
