# SPDX-License-Identifier: MIT
"""Cases from files, TOML text and Python dicts: one parser, the CLI's validation and messages."""
from __future__ import annotations

import numpy as np
import pytest

import frictopt


def test_load_case_reads_the_demo(demo_case: frictopt.Case) -> None:
    assert demo_case.dim == 3
    assert demo_case.num_design_variables == 16
    assert demo_case.name == "punch-anisotropic"
    assert demo_case.cost_kind == "target_pressure"
    assert demo_case.young == 7.0e10  # Pa
    np.testing.assert_array_equal(demo_case.initial_design[:4], [1.5e-3, 1.0e-3, 1.0e-3, 1.5e-3])
    assert demo_case.friction_law.kind == "polygon"
    assert "punch-anisotropic" in repr(demo_case)


def test_parse_case_error_names_field_value_and_expectation(demo_case: frictopt.Case) -> None:
    text = demo_case.toml.replace("poisson = 0.33", "poisson = 0.6")
    with pytest.raises(ValueError, match=r"my\.toml:\d+: material\.poisson = 0\.6; expected 0 <= poisson < 0\.5"):
        frictopt.parse_case(text, "my.toml")


def test_unknown_key_and_syntax_errors_are_value_errors(demo_case: frictopt.Case) -> None:
    with pytest.raises(ValueError, match=r"x\.toml:\d+: unknown key 'output2' \(did you mean 'output'\?\)"):
        frictopt.parse_case(demo_case.toml + "\n[output2]\ncolour = 1\n", "x.toml")
    with pytest.raises(ValueError, match="TOML syntax error"):
        frictopt.parse_case("[geometry\n", "broken.toml")


def test_missing_file_is_a_value_error_naming_it(tmp_path) -> None:
    with pytest.raises(ValueError, match="nowhere.toml"):
        frictopt.load_case(tmp_path / "nowhere.toml")


def test_from_dict_round_trip_gives_the_same_state(demo_case: frictopt.Case) -> None:
    tables = demo_case.to_dict()
    tables["mesh"]["cells"] = [6, 6, 3]
    built = frictopt.Case.from_dict(tables, origin="built.toml")
    same = demo_case.with_overrides(mesh={"cells": [6, 6, 3]})
    a = frictopt.Body(built).solve()
    b = frictopt.Body(same).solve()
    assert a.converged and b.converged
    np.testing.assert_array_equal(a.displacement, b.displacement)


def test_from_dict_validates_like_a_file() -> None:
    with pytest.raises(ValueError, match=r"built\.toml.*geometry"):
        frictopt.Case.from_dict({"geometry": {"dim": 4}}, origin="built.toml")


def test_with_overrides_merges_removes_and_revalidates(coarse_case: frictopt.Case) -> None:
    iso = coarse_case.with_overrides(contact={"friction": {"kind": "isotropic", "mu": 0.3, "mu_vertices": None, "n": 8}})
    assert iso.friction_law.kind == "regular_polygon"
    assert iso.friction_law.mu(0.1) == pytest.approx(0.3 * np.cos(np.pi / 8 - 0.1), rel=1e-12)
    with pytest.raises(ValueError, match="with overrides"):
        coarse_case.with_overrides(mesh={"cells": [0, 8, 4]})
    assert coarse_case.to_dict()["mesh"]["cells"] == [8, 8, 4]


def test_to_toml_writes_tables_arrays_of_tables_and_numbers() -> None:
    text = frictopt.to_toml({"a": {"x": 1e-5, "y": [1, 2], "s": "q\"t"}, "d": [{"face": "top"}, {"face": "left"}]})
    assert "[a]" in text and "x = 1e-05" in text and "[[d]]" in text and 's = "q\\"t"' in text
    import tomllib
    assert tomllib.loads(text) == {"a": {"x": 1e-5, "y": [1, 2], "s": "q\"t"}, "d": [{"face": "top"}, {"face": "left"}]}


def test_a_geo_that_runs_the_shell_is_refused_unless_trusted(root, tmp_path) -> None:
    """A .geo named by a case is read restricted (docs/meshes.md, "A .geo file runs no code"):
    `System` is refused by load_case and parse_case, and runs only with trust_geo=True."""
    marker = tmp_path / "PWNED"
    source = root / "cases2d" / "gmsh-body"
    (tmp_path / "body.geo").write_text((source / "body.geo").read_text() + f'System "touch {marker}";\n')
    text = (source / "case.toml").read_text()
    (tmp_path / "case.toml").write_text(text)
    refusal = r"body\.geo:\d+: the \.geo uses 'System', which runs a shell command"
    with pytest.raises(ValueError, match=refusal):
        frictopt.load_case(tmp_path / "case.toml")
    with pytest.raises(ValueError, match=refusal):
        frictopt.parse_case(text, str(tmp_path / "case.toml"))
    with pytest.raises(ValueError, match=refusal):
        frictopt.Case.from_file(tmp_path / "case.toml")
    assert not marker.exists()
    # The explicit opt-in runs every Gmsh command, for a file the user has read.
    trusted = frictopt.load_case(tmp_path / "case.toml", trust_geo=True)
    assert trusted.dim == 2
    assert marker.exists()
    marker.unlink()
    assert frictopt.parse_case(text, str(tmp_path / "case.toml"), trust_geo=True).dim == 2
    assert marker.exists()
    # The default is restored after a trusted read: the next one is restricted again.
    with pytest.raises(ValueError, match=refusal):
        frictopt.load_case(tmp_path / "case.toml")
