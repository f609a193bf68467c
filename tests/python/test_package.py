# SPDX-License-Identifier: MIT
"""The Pythonic surface: docstrings everywhere, the type stub ships and covers the API, the
interpreter is Debian's."""
from __future__ import annotations

import inspect
import pathlib
import pydoc
import sys

import frictopt


def public_objects():
    for name in frictopt.__all__:
        obj = getattr(frictopt, name)
        if callable(obj) or inspect.isclass(obj):
            yield name, obj


def test_every_function_class_and_method_has_a_docstring() -> None:
    missing = []
    for name, obj in public_objects():
        if not (obj.__doc__ or "").strip():
            missing.append(name)
        if inspect.isclass(obj) and obj.__module__.startswith("frictopt"):
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                doc = getattr(member, "__doc__", None) or getattr(getattr(member, "fget", None), "__doc__", None)
                if not (doc or "").strip():
                    missing.append(f"{name}.{attr}")
    assert not missing, f"no docstring: {missing}"


def test_help_of_body_reads_well() -> None:
    text = pydoc.render_doc(frictopt.Body, renderer=pydoc.plaintext)
    assert "solve(" in text and "Example" in text and "[m]" in text
    assert "SI units" in pydoc.render_doc(frictopt, renderer=pydoc.plaintext)


def test_the_stub_ships_with_the_package_and_covers_the_api() -> None:
    package = pathlib.Path(frictopt.__file__).parent
    stub = (package / "_frictopt.pyi").read_text()
    import ast
    ast.parse(stub)  # a syntactically valid stub
    assert (package / "py.typed").exists()
    for name, obj in public_objects():
        if obj.__module__ == "frictopt._frictopt":
            assert (f"class {name}" in stub) or (f"def {name}(" in stub), name


def test_built_for_the_running_interpreter() -> None:
    # ctest runs the interpreter CMake built the module for (Debian's /usr/bin/python3, whose
    # python3-numpy and python3-vtk9 the project uses); the extension's ABI tag must be its own.
    import sysconfig
    assert frictopt._frictopt.__file__.endswith(sysconfig.get_config_var("EXT_SUFFIX"))
