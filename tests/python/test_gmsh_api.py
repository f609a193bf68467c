# SPDX-License-Identifier: MIT
"""A mesh scripted with the Gmsh Python API (Debian's python3-gmsh, docs/meshes.md) is a body
frictopt reads: an OpenCASCADE box meshed in tetrahedra, written as .msh, named by a case,
subdivided into hexahedra and solved pressed onto the foundation."""
from __future__ import annotations

import pytest

import frictopt

gmsh = pytest.importorskip("gmsh")


def test_a_mesh_scripted_with_the_gmsh_api_is_a_body(tmp_path) -> None:
    msh = tmp_path / "box.msh"
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("box")
        gmsh.model.occ.addBox(0.0, 0.0, 0.0, 1.0, 1.0, 0.4)
        gmsh.model.occ.synchronize()
        # The box's faces: 1 x1 = 0, 2 x1 = 1, 3 x2 = 0, 4 x2 = 1, 5 x3 = 0, 6 x3 = 0.4.
        gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, [1]), "Body")
        gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, [5]), "Bottom")
        gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, [6]), "Top")
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.4)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(msh))
    finally:
        gmsh.finalize()
    case = frictopt.Case.from_dict({
        "geometry": {"dim": 3},
        "mesh": {"file": str(msh), "contact": "Bottom"},
        "material": {"young": 7.0e10, "poisson": 0.3},
        "dirichlet": [{"boundary": "Top", "displacement": [0.0, 0.0, -1.0e-5]}],
        "design": {"control_points": [2, 2], "initial": 0.0, "upper_bound": 1.0e-3},
        "contact": {"friction": {"kind": "isotropic", "mu": 0.3, "n": 8}},
    }, str(tmp_path / "case.toml"))
    body = frictopt.Body(case)
    state = body.solve()
    assert state.summary.status == "converged"
    contact = state.summary.contact
    # A flat box pressed by 10 µm over 0.4 m: about E·ε·A (ν and the foundation's friction
    # stiffen it a little), carried by every contact node.
    assert 0.9 * 7.0e10 * 1.0e-5 / 0.4 < contact.total_normal_force < 1.6 * 7.0e10 * 1.0e-5 / 0.4
    assert contact.num_separated == 0
