// SPDX-License-Identifier: MIT
// The extension module frictopt._frictopt; the package python/frictopt re-exports it with the
// pure-Python helpers (docs/python.md).
#include <pybind11/pybind11.h>

#include <filesystem>

#include "bindings.hpp"
#include "frictopt/core/error.hpp"

PYBIND11_MODULE(_frictopt, m) {
  namespace py = pybind11;
  m.doc() =
      "frictopt: shape optimization of elastic bodies in contact with (anisotropic) Coulomb friction.\n\n"
      "SI units throughout: lengths in m, forces in N (2D: N per metre of thickness), stresses and\n"
      "pressures in Pa, energies in J. Bad input raises ValueError with the message of the case\n"
      "files and the CLI; a numerical failure is a status in the returned summary, not an exception.";
  // The C++ error types keep their messages: InvalidInput (bad input at an API boundary) is a
  // ValueError, a file-system failure an OSError; anything else keeps pybind11's mapping.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const frictopt::InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::filesystem::filesystem_error& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  frictopt::python::bind_friction_law(m);
  frictopt::python::bind_case(m);
  frictopt::python::bind_body(m);
  frictopt::python::bind_oracle(m);
  frictopt::python::bind_optimize(m);
  frictopt::python::bind_identification(m);
  frictopt::python::bind_experiment(m);
  frictopt::python::bind_shape_export(m);
}
