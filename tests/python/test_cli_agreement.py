# SPDX-License-Identifier: MIT
"""The module and the CLI agree on the same case to 1e-12: summary.json fields and VTK arrays."""
from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import frictopt
from compare import assert_same

def read_vtu(path) -> dict[str, np.ndarray]:
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    data = reader.GetOutput().GetPointData()
    return {data.GetArrayName(k): vtk_to_numpy(data.GetArray(k)) for k in range(data.GetNumberOfArrays())}


@pytest.mark.parametrize("case_path", ["cases3d/punch-anisotropic/case.toml", "cases2d/ex521-target-pressure/case.toml"])
def test_solve_agrees_with_the_cli(root, tmp_path, frictopt_binary, case_path: str) -> None:
    cli_dir = tmp_path / "cli"
    subprocess.run([frictopt_binary, "solve", case_path, "-o", cli_dir], cwd=root, check=True, capture_output=True)
    cli = json.loads((cli_dir / "summary.json").read_text())

    case = frictopt.load_case(root / case_path)
    # The CLI names the case by the path it was given; the Python summary by the one loaded.
    cli["case"] = case.origin
    body = frictopt.Body(case)
    state = body.solve()
    assert_same(cli, state.summary)

    cli_vtu = read_vtu(cli_dir / f"{case.name}.vtu")
    np.testing.assert_allclose(state.displacement, cli_vtu["displacement"][:, : body.dim], rtol=1e-12, atol=0)
    nodes = body.contact_nodes
    np.testing.assert_allclose(state.pressure, cli_vtu["contact_pressure"][nodes], rtol=1e-12, atol=0)
    np.testing.assert_array_equal(state.contact_status, cli_vtu["contact_status"][nodes])
    np.testing.assert_allclose(state.von_mises, cli_vtu["von_mises"], rtol=1e-12, atol=0)

    # Body.write_vtk writes the same file content as the CLI.
    body.write_vtk(tmp_path / "py.vtu", state)
    py_vtu = read_vtu(tmp_path / "py.vtu")
    assert py_vtu.keys() == cli_vtu.keys()
    for name, values in cli_vtu.items():
        np.testing.assert_allclose(py_vtu[name], values, rtol=1e-12, atol=0, err_msg=name)


def test_error_messages_match_the_cli(root, tmp_path, frictopt_binary, demo_case) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(demo_case.toml.replace("young = 7.0e10", "young = -7.0e10"))
    run = subprocess.run([frictopt_binary, "solve", bad, "-o", tmp_path / "out"], capture_output=True, text=True)
    assert run.returncode == 2
    with pytest.raises(ValueError) as error:
        frictopt.load_case(bad)
    assert str(error.value) in run.stderr
    assert "material.young" in str(error.value)
