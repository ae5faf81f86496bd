#pragma once
// Resting towers of boxes as contact problems with a body-space W (four corner contacts per face),
// their statics and their arrival velocities (ContactProblem::arrival): the fixtures of
// StickingStartTest and SteadyWarmStartTest.
#include <gtest/gtest.h>
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolverOptions.hpp>
#include <coulomb/solvers/StickingStart.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace coulomb::solvers::testing {

constexpr double kMass = 2.0, kHalf = 0.5, kGravity = 9.81, kStep = 0.01;

// `boxes` unit boxes (mass 2 kg) stacked on the ground, four corner contacts per face, normal +z
// from the lower body (side 0; the ground is static) to the upper (side 1); q = J v* with
// v* = (0, 0, -g h) for every box. `lateral` adds a sideways velocity to the top box's v*.
inline ContactProblem tower(int boxes, double mu, double lateral = 0.0) {
  const int contacts = 4 * boxes;
  auto factors = std::make_shared<BodySpaceDelassus>(boxes, std::vector<int>(contacts, 3));
  const double inertia = kMass * (2 * kHalf) * (2 * kHalf) / 6.0;  // a cube about its centre
  Eigen::Matrix<double, 6, 6> inverseMass = Eigen::Matrix<double, 6, 6>::Zero();
  inverseMass.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / kMass);
  inverseMass.bottomRightCorner<3, 3>().diagonal().setConstant(1.0 / inertia);
  std::vector<Eigen::Matrix<double, 6, 1>> freeVelocity(boxes, Eigen::Matrix<double, 6, 1>::Zero());
  for (auto& v : freeVelocity) v[2] = -kGravity * kStep;
  freeVelocity.back()[0] = lateral;
  const Eigen::Vector3d n(0, 0, 1), t1(1, 0, 0), t2(0, 1, 0);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3 * contacts);
  for (int k = 0; k < boxes; ++k)
    for (int corner = 0; corner < 4; ++corner) {
      const int c = 4 * k + corner;
      const double x = (corner & 1) ? kHalf : -kHalf, y = (corner & 2) ? kHalf : -kHalf;
      for (int side = 0; side < 2; ++side) {
        const int body = side == 1 ? k : k - 1;  // the box above, or the one below (ground: -1)
        if (body < 0) continue;
        const Eigen::Vector3d arm(x, y, side == 1 ? -kHalf : kHalf);  // from the body's centre
        const double sign = side == 1 ? 1.0 : -1.0;
        Eigen::Matrix<double, 3, 6> J;
        int row = 0;
        for (const Eigen::Vector3d& d : {n, t1, t2}) {
          J.block<1, 3>(row, 0) = sign * d.transpose();
          J.block<1, 3>(row, 3) = sign * arm.cross(d).transpose();
          ++row;
        }
        factors->setSide(c, side, body, J, inverseMass * J.transpose());
        q.segment<3>(3 * c) += J * freeVelocity[static_cast<std::size_t>(body)];
      }
    }
  return ContactProblem::contacts(DelassusOperator::bodySpace(factors), q,
                                  std::vector<double>(contacts, mu), "tower");
}

// The tower with a warm start in which each corner carries only its own box's weight: the load
// of the boxes above still has to move down, which Gauss-Seidel does one layer per sweep.
inline ContactProblem towerWarmStartedWithOwnWeights(int boxes, double mu, double lateral = 0.0) {
  ContactProblem p = tower(boxes, mu, lateral);
  Eigen::VectorXd warm = Eigen::VectorXd::Zero(p.size());
  for (int c = 0; c < 4 * boxes; ++c) warm[3 * c] = kMass * kGravity * kStep / 4.0;
  p.warmStart = warm;
  return p;
}

inline SolverOptions restartOptions(double tolerance, int maxIterations) {
  SolverOptions options;
  options.tolerance = tolerance;
  options.maxIterations = maxIterations;
  options.stickingStart = true;
  return options;
}

// Each face of the resting tower carries the weight of the boxes above it (and its own box).
inline void expectFacesCarryTheWeightAbove(const Eigen::VectorXd& impulses, int boxes) {
  for (int k = 0; k < boxes; ++k) {
    double load = 0.0;
    for (int c = 4 * k; c < 4 * k + 4; ++c) load += impulses[3 * c];
    const double weight = (boxes - k) * kMass * kGravity * kStep;
    EXPECT_NEAR(load, weight, 1e-6 * weight) << k;
  }
}

// The rows' velocities J v_k of the bodies' arrival velocities (ContactProblem::arrival).
inline Eigen::VectorXd arrivalRowVelocities(const ContactProblem& p) {
  const BodySpaceDelassus& factors = *p.W.bodySpaceOperator();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(p.size());
  factors.addRowVelocities(p.arrival, d.data());
  return d;
}

// The resting tower of `boxes` boxes whose bodies arrive with vertical velocity errors
// +-epsilon (alternating by box; ContactProblem::arrival): q = q0 + J v_k. Warm-started with the
// exact answer of the step before, which arrived with the opposite errors (q0 - J v_k): the warm
// start misses by twice the arrival, the pattern of a stack whose accepted warm starts leave
// errors within the tolerance.
inline ContactProblem towerArrivingWithErrors(int boxes, double epsilon) {
  ContactProblem p = tower(boxes, 0.5);
  p.arrival = Eigen::VectorXd::Zero(6 * boxes);
  for (int k = 0; k < boxes; ++k) p.arrival[6 * k + 2] = (k % 2 == 0 ? 1.0 : -1.0) * epsilon;
  const Eigen::VectorXd d = arrivalRowVelocities(p);
  StickingStart before;
  const Eigen::VectorXd previousQ = p.q - d;
  EXPECT_TRUE(before.compute(*p.W.bodySpaceOperator(), previousQ, p.blocks, nullptr));
  p.warmStart = before.start();
  p.q += d;
  return p;
}

// q without the arrival: the next step's, for bodies that the answer stopped.
inline Eigen::VectorXd steadyQ(const ContactProblem& p) {
  return p.q - arrivalRowVelocities(p);
}

inline double residualFor(const ContactProblem& p, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& r) {
  ContactProblem next = p;
  next.q = q;
  return commonResidual(next, r).relative;
}

}  // namespace coulomb::solvers::testing
