#pragma once
// Exact solution of the one-contact problem of blocked Gauss-Seidel (docs/solver-derivations.md
// (4.1)):
//   find r in R^3 with u = W r + q~ and K* ∋ u + mu ||u_T|| e_N  _|_  r ∈ K,
// W the contact's 3x3 diagonal block (possibly non-symmetric, tiny or huge), by Algorithm 4.1:
// closed forms (take-off, frictionless, stick, isotropic slip), a local Alart-Curnier Newton,
// an angle scan for the general slip case (4.5), projection iterations as the last resort.
#include <Eigen/Core>
#include <Eigen/LU>

namespace coulomb::solvers {

struct LocalContactData {
  Eigen::Matrix3d W;
  Eigen::PartialPivLU<Eigen::Matrix3d> lu;
  bool invertible = false;  // |det| > 1e-12 prod |W_ii| (4.3)
  double rho = 0.0;         // 1/lambda_max(sym W): projection step and error scale (3.3), (4.6)
  double rhoN = 0.0;        // 1/W_NN (local Newton, docs/solver-derivations.md section 4)
  double rhoT = 0.0;        // 1/lambda_max(sym W_TT)
  static LocalContactData from(const Eigen::Matrix3d& W);
};

struct LocalSolverSettings {
  double tolerance = 1e-14;        // [-] on the scale-free local error (4.6)
  int newtonIterations = 30;       // local Newton iterations per start
  int lineSearchTrials = 20;       // Goldstein-Price trials (Algorithm 5.2)
  int scanAngles = 72;             // angle grid of (4.5)
  int projectionIterations = 100;  // last resort (3.3)-(3.4)
};

enum class LocalStage {
  TakeOff,
  Frictionless,
  Stick,
  IsotropicSlip,
  Newton,
  AngleScan,
  Projection,
  Incoming
};

struct LocalResult {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  double error = 0.0;  // (4.6)
  LocalStage stage = LocalStage::TakeOff;
};

// Scale-free local error (4.6): ||r - P_K(r - rho û)|| / (||r|| + rho ||q~||), rho = data.rho.
double localError(const LocalContactData& data, const Eigen::Vector3d& qTilde, double mu,
                  const Eigen::Vector3d& r);

// Algorithm 4.1. Returns the best candidate by (4.6), never worse than `incoming`.
LocalResult solveLocalContact(const LocalContactData& data, const Eigen::Vector3d& qTilde,
                              double mu, const Eigen::Vector3d& incoming,
                              const LocalSolverSettings& settings = {});

// The local Alart-Curnier Newton alone (exposed for tests): from `start`, at most
// settings.newtonIterations steps, returns the best iterate.
LocalResult localNewton(const LocalContactData& data, const Eigen::Vector3d& qTilde, double mu,
                        const Eigen::Vector3d& start, const LocalSolverSettings& settings);

}  // namespace coulomb::solvers
