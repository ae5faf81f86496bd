#pragma once
// The parts of the Python module (docs/python.md), one file each; Module.cpp calls them in order.
#include <pybind11/pybind11.h>

namespace coulomb::python {

void bindProblem(pybind11::module_& m);  // Block, ContactProblem, fc3d files (ProblemBindings.cpp)
void bindSolve(pybind11::module_& m);    // solvers(), solve(), residual() (SolveBindings.cpp)
void bindCapture(pybind11::module_& m);  // scenes(), capture_problems() (CaptureBindings.cpp)
void bindRun(pybind11::module_& m);      // run(), run_batch(), conformance cases (RunBindings.cpp)
void bindWorld(pybind11::module_& m);    // World, Robot (WorldBindings.cpp)
void bindQueries(pybind11::module_& m);  // World's scene queries (QueryBindings.cpp)
void bindEvents(pybind11::module_& m);   // World's events, kinematic targets (EventBindings.cpp)

}  // namespace coulomb::python
