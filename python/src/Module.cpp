// The `coulomb._coulomb` extension module (docs/python.md); python/coulomb/__init__.py re-exports
// it. Engine errors become coulomb.Error (a ValueError) carrying the engine's message.
#include <coulomb/engine/CoulombError.hpp>

#include "Bindings.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_coulomb, m) {
  m.doc() = "Coulomb: rigid-body contact with exact Coulomb friction (docs/python.md)";
  py::register_exception<coulomb::engine::CoulombError>(m, "Error", PyExc_ValueError);
  coulomb::python::bindProblem(m);
  coulomb::python::bindSolve(m);
  coulomb::python::bindCapture(m);
  coulomb::python::bindRun(m);
  coulomb::python::bindWorld(m);
  coulomb::python::bindQueries(m);
  coulomb::python::bindEvents(m);
}
