# SPDX-License-Identifier: MIT
"""Identification of friction coefficients from (synthetic) measurements."""
from __future__ import annotations

import numpy as np
import pytest

import frictopt


@pytest.fixture(scope="module")
def case(root) -> frictopt.Case:
    return frictopt.load_case(root / "cases3d" / "identify-anisotropic" / "case.toml")


def test_noise_free_synthetic_data_recover_the_law(case: frictopt.Case) -> None:
    data = frictopt.synthetic_measurements(case, noise=False)
    assert len(data) > 4 and isinstance(data[0], frictopt.Measurement)
    result = frictopt.identify(case, data)
    assert result.status == "converged", result.message
    truth = [0.2, 0.45, 0.25, 0.4]  # the case's mu_vertices
    estimates = {e.name: e.value for e in result.estimates}
    for j, mu in enumerate(truth):
        name = f"mu_vertices[{j}]"
        if result.estimates[j].identifiability == "determined":
            assert estimates[name] == pytest.approx(mu, rel=1e-6)
    assert result.residuals.shape == result.predictions.shape == (len(data),)
    assert result.covariance.shape == (4, 4)


def test_measurements_round_trip_and_errors(case: frictopt.Case, tmp_path) -> None:
    data = frictopt.read_measurements(case.measurements_path)
    frictopt.write_measurements(tmp_path / "m.csv", data, "copy")
    again = frictopt.read_measurements(tmp_path / "m.csv")
    assert [m.value for m in again] == [m.value for m in data]
    with pytest.raises(ValueError, match="quantity"):
        frictopt.Measurement("shear_force", 1.0)
    with pytest.raises(ValueError, match="node"):
        frictopt.identify(case, [frictopt.Measurement("normal_force", 1.0, 0.1, node=100000)])
    with pytest.raises(ValueError, match="identification"):
        frictopt.identify(frictopt.load_case(case.origin).with_overrides(identification=None))
