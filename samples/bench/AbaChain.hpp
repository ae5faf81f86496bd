#pragma once
// Articulations for the ABA benchmarks (bench/ArticulationBench, `coulomb bench --parts aba`):
// a serial revolute snake of any length and a smooth state to evaluate it at.
#include <coulomb/joints/tree/Articulation.hpp>

#include <Eigen/Core>

namespace coulomb::samples {

/// n revolute links 0.1 m apart, axes alternating y and x (a snake), boxes of 1 kg.
joints::tree::Articulation serialChain(int n);

/// v_i = 0.5 sin(phase + 0.7 i): a smooth, non-trivial q, qd or tau of size n.
Eigen::VectorXd wave(int n, double phase);

/// |M qdd + h - tau|_inf for qdd from ABA at (q, qd, tau) = waves 0.1, 0.2, 0.3: how exactly ABA
/// solves the equations of motion built by CRBA and RNEA.
double abaResidual(const joints::tree::Articulation& tree);

}  // namespace coulomb::samples
