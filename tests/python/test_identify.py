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


@pytest.fixture(scope="module")
def lay_case(root) -> frictopt.Case:
    """cases3d/identify-lay: two tribometer experiments (0° and 90°), measurements inline."""
    return frictopt.load_case(root / "cases3d" / "identify-lay" / "case.toml")


def test_a_measurement_list_needs_no_file_in_the_case(case: frictopt.Case) -> None:
    data = frictopt.synthetic_measurements(case, noise=False)
    no_file = case.with_overrides(identification={"measurements": None})
    assert no_file.has_identification and no_file.measurements_path is None
    with pytest.raises(ValueError, match=r"\[identification\] gives no measurements"):
        frictopt.identify(no_file)
    # The same rows as dicts and as tuples of Measurement's arguments.
    rows = [{"quantity": m.quantity, "value": m.value, "sigma": m.sigma, "node": m.node,
             "point": None if m.point is None else list(m.point)} for m in data]
    result = frictopt.identify(no_file, rows)
    assert result.status == "converged", result.message
    assert [e.value for e in result.estimates] == pytest.approx([0.2, 0.45, 0.25, 0.4], rel=1e-6)
    assert [e.name for e in result.experiments] == ["case"]
    tuples = [(m.quantity, m.value, m.sigma, m.node, m.point) for m in data]
    again = frictopt.identify(no_file, tuples)
    assert [e.value for e in again.estimates] == [e.value for e in result.estimates]


def test_a_list_of_experiments_separates_the_two_coefficients(lay_case: frictopt.Case) -> None:
    experiments = frictopt.synthetic_experiments(lay_case, noise=False)
    assert [x.name for x in experiments] == ["along", "across"]
    assert experiments[1].orientation_deg == pytest.approx(90.0)
    assert experiments[1].dirichlet_scale == [0.8]
    joint = frictopt.identify(lay_case, experiments=experiments)
    assert joint.status == "converged", joint.message
    assert [e.identifiability for e in joint.estimates] == ["determined", "determined"]
    assert [e.value for e in joint.estimates] == pytest.approx([0.25, 0.4], abs=1e-10)
    assert [x.name for x in joint.experiments] == ["along", "across"]
    assert [x.measurements for x in joint.experiments] == [2, 2]
    # The same experiments as dicts, their measurements as lists of dicts.
    as_dicts = [{"name": x.name, "orientation_deg": x.orientation_deg, "dirichlet_scale": x.dirichlet_scale or None,
                 "measurements": [{"quantity": m.quantity, "value": m.value, "sigma": m.sigma} for m in x.measurements]}
                for x in experiments]
    again = frictopt.identify(lay_case, experiments=as_dicts)
    assert [e.value for e in again.estimates] == pytest.approx([0.25, 0.4], abs=1e-10)
    # One experiment alone: sliding along the lay says nothing about μ across it.
    alone = frictopt.identify(lay_case, experiments=[experiments[0]])
    assert alone.estimates[0].value == pytest.approx(0.25, abs=1e-10)
    assert alone.estimates[1].identifiability == "not_determined"
    assert np.isnan(alone.estimates[1].standard_deviation)
    # Turned the other way round, the experiment reads μ across the lay.
    turned = frictopt.Experiment("turned", experiments[1].measurements, orientation_deg=90.0, dirichlet_scale=0.8)
    assert frictopt.identify(lay_case, experiments=[turned]).estimates[1].value == pytest.approx(0.4, abs=1e-10)


def test_experiment_errors_name_the_way_out(lay_case: frictopt.Case) -> None:
    rows = [frictopt.Measurement("total_normal_force", 1.0, 0.1)]
    with pytest.raises(ValueError, match=r"experiments=\[\.\.\.\]"):
        frictopt.identify(lay_case, rows)
    with pytest.raises(ValueError, match="not both"):
        frictopt.identify(lay_case, rows, experiments=[frictopt.Experiment("a", rows)])
    with pytest.raises(ValueError, match=r"experiment\[1\]\.name = \"a\" is the name of experiment\[0\]"):
        frictopt.identify(lay_case, experiments=[frictopt.Experiment("a", rows), frictopt.Experiment("a", rows)])
    with pytest.raises(ValueError, match="dirichlet_scale: 2 scale"):
        frictopt.identify(lay_case, experiments=[frictopt.Experiment("a", rows, dirichlet_scale=[1.0, 2.0])])
    with pytest.raises(ValueError, match="expected a CSV path or a list"):
        frictopt.Experiment("a", 3)
