# SPDX-License-Identifier: MIT
"""frictopt: shape optimization of elastic bodies in contact with (anisotropic) Coulomb friction.

The Python interface to the frictopt C++ library (docs/python.md):

* cases: ``load_case(path)``, ``parse_case(text)``, ``Case.from_dict(tables)``,
  ``case.with_overrides(...)`` — every route runs the case-file parser, so bad input raises
  ValueError with the CLI's message (naming file, field, value and expectation);
* the state: ``Body(case).solve(alpha)`` → ``State`` with numpy arrays (displacement, stresses,
  normal and tangential forces, pressure, traction, slip, stick/slip status per contact node);
* friction laws: ``FrictionLaw`` (μ(θ) by the support function, vertices, projection);
* the shape problem: ``Oracle(case)`` for Θ(α) and a subgradient, ``optimize(...)`` with a
  per-iteration callback and resumable run directories, ``certify``, ``check_gradient``,
  ``identify``; export with ``Body.write_vtk`` and ``Body.export_fclib``.

Units are SI throughout: m, N (2D: N per metre of thickness), Pa, J, s. A numerical failure is a
status in the returned object (as in C++), never an exception; Ctrl-C stops an optimization at
the next iteration with its run directory intact.
"""
from __future__ import annotations

import tomllib
from collections.abc import Mapping
from typing import Any

from ._frictopt import (
    Body,
    Case,
    Evaluation,
    Experiment,
    FrictionLaw,
    Measurement,
    Oracle,
    State,
    certify,
    check_gradient,
    experiment,
    export_shape,
    identify,
    load_case,
    optimize,
    parse_case,
    read_measurements,
    solve_program,
    synthetic_experiments,
    synthetic_measurements,
    write_measurements,
)
from ._summary import Summary
from ._toml import merge as _merge
from ._toml import to_toml

__all__ = [
    "Body", "Case", "Evaluation", "Experiment", "FrictionLaw", "Measurement", "Oracle", "State", "Summary",
    "certify", "check_gradient", "experiment", "export_shape", "identify", "load_case", "optimize", "parse_case",
    "read_measurements", "solve_program", "synthetic_experiments", "synthetic_measurements", "write_measurements", "to_toml",
    "STATUS_SEPARATED", "STATUS_STICK", "STATUS_SLIP",
]

#: Values of State.contact_status.
STATUS_SEPARATED, STATUS_STICK, STATUS_SLIP = 0, 1, 2


def _case_from_dict(tables: Mapping[str, Any], origin: str = "<python>") -> Case:
    """A case from nested dicts with the tables of a case file ({"geometry": {...}, "mesh": {...},
    "dirichlet": [{...}], ...}; docs/case-format.md), validated by the case-file parser: a bad field
    raises ValueError naming it. ``origin`` prefixes messages; relative paths resolve against its
    directory."""
    return parse_case(to_toml(tables), origin)


def _case_to_dict(self: Case) -> dict[str, Any]:
    """The case's tables as nested dicts (tomllib reading of ``case.toml``)."""
    return tomllib.loads(self.toml)


def _case_with_overrides(self: Case, overrides: Mapping[str, Any] | None = None, **tables: Any) -> Case:
    """A new case: this one with tables merged in (dicts merge recursively, other values replace,
    None removes a key), validated again by the case-file parser, e.g.
    ``case.with_overrides(mesh={"cells": [8, 8, 4]}, contact={"friction": {"mu_vertices": [0.3, 0.2, 0.3, 0.2]}})``."""
    merged = _merge(self.to_dict(), dict(overrides or {}, **tables))
    # Line numbers in messages refer to the merged text, hence the marked origin (its directory
    # still resolves relative paths).
    origin = self.origin if self.origin.endswith(" (with overrides)") else self.origin + " (with overrides)"
    return parse_case(to_toml(merged), origin)


Case.from_dict = staticmethod(_case_from_dict)
Case.to_dict = _case_to_dict
Case.with_overrides = _case_with_overrides
