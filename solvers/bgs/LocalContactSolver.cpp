#include <coulomb/solvers/bgs/LocalContactSolver.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/newton/NewtonFunction.hpp>
#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace coulomb::solvers {

LocalContactData LocalContactData::from(const Eigen::Matrix3d& W) {
  LocalContactData d;
  d.W = W;
  d.lu.compute(W);
  const double prodDiag = std::abs(W(0, 0) * W(1, 1) * W(2, 2));
  d.invertible = std::abs(d.lu.determinant()) > 1e-12 * prodDiag;
  d.rho = inverseSpectralRadius(W);
  d.rhoN = W(0, 0) > 0 ? 1.0 / W(0, 0) : d.rho;
  d.rhoT = inverseTangentSpectralRadius(W);
  if (d.rhoT <= 0) d.rhoT = d.rho;
  return d;
}

double localError(const LocalContactData& data, const Eigen::Vector3d& qt, double mu,
                  const Eigen::Vector3d& r) {
  const Eigen::Vector3d u = data.W * r + qt;
  const double rho = data.rho;
  double x[3] = {r[0] - rho * (u[0] + mu * std::hypot(u[1], u[2])), r[1] - rho * u[1],
                 r[2] - rho * u[2]};
  projectOntoCone(x, mu);
  const double num = std::sqrt((r[0] - x[0]) * (r[0] - x[0]) + (r[1] - x[1]) * (r[1] - x[1]) +
                               (r[2] - x[2]) * (r[2] - x[2]));
  const double den = r.norm() + rho * qt.norm();
  return den > 0 ? num / den : num;
}

namespace {

const AlartCurnierFunction kAlartCurnier{};

double merit(const LocalContactData& d, const Eigen::Vector3d& qt, double mu,
             const Eigen::Vector3d& r) {
  Eigen::Vector3d phi;
  Eigen::Matrix3d A, B;
  kAlartCurnier.contact(r, d.W * r + qt, mu, d.rhoN, d.rhoT, phi, A, B);
  return 0.5 * phi.squaredNorm();
}

void keepBetter(LocalResult& best, const Eigen::Vector3d& r, double e, LocalStage stage) {
  if (r.allFinite() && e < best.error) best = {r, e, stage};
}

}  // namespace

LocalResult localNewton(const LocalContactData& d, const Eigen::Vector3d& qt, double mu,
                        const Eigen::Vector3d& start, const LocalSolverSettings& s) {
  constexpr double m1 = 0.1, m2 = 0.9;  // (5.10)
  LocalResult best{start, localError(d, qt, mu, start), LocalStage::Newton};
  Eigen::Vector3d r = start;
  for (int it = 0; it < s.newtonIterations && best.error > s.tolerance; ++it) {
    const Eigen::Vector3d u = d.W * r + qt;
    Eigen::Vector3d phi;
    Eigen::Matrix3d A, B;
    kAlartCurnier.contact(r, u, mu, d.rhoN, d.rhoT, phi, A, B);
    const double psi0 = 0.5 * phi.squaredNorm();
    if (psi0 == 0.0) break;
    const Eigen::Matrix3d J = A * d.W + B;  // (5.5)
    Eigen::Vector3d dir = J.partialPivLu().solve(-phi);
    if (!dir.allFinite() || (J * dir + phi).norm() > 1e-8 * phi.norm()) {
      // Singular local Jacobian: shift W as in (5.8) (tiny, relative), else steepest descent.
      const double sigma = 1e-10 / d.rho;
      const Eigen::Matrix3d Js = A * (d.W + sigma * Eigen::Matrix3d::Identity()) + B;
      dir = Js.partialPivLu().solve(-phi);
      if (!dir.allFinite()) dir = -J.transpose() * phi;
    }
    double slope = phi.dot(J * dir);
    if (!(slope < 0)) {
      dir = -J.transpose() * phi;
      slope = -dir.squaredNorm();
      if (!(slope < 0)) break;
    }
    // Goldstein-Price, Algorithm 5.2 (AC11 Algorithm 2 corrected: start at alpha = 1).
    double alpha = 1.0, lo = 0.0, hi = std::numeric_limits<double>::infinity();
    double bestAlpha = 0.0, bestPsi = psi0;
    bool accepted = false;
    for (int t = 0; t < s.lineSearchTrials; ++t) {
      const double psi = merit(d, qt, mu, r + alpha * dir);
      if (psi < bestPsi) bestPsi = psi, bestAlpha = alpha;
      const double slopeAvg = (psi - psi0) / alpha;
      if (slopeAvg < m2 * slope) {
        lo = alpha;
      } else if (slopeAvg > m1 * slope) {
        hi = alpha;
      } else {
        accepted = true;
        break;
      }
      alpha = std::isfinite(hi) ? 0.5 * (lo + hi) : 10.0 * alpha;
    }
    if (!accepted) alpha = bestAlpha;
    if (alpha == 0.0) break;
    r += alpha * dir;
    keepBetter(best, r, localError(d, qt, mu, r), LocalStage::Newton);
  }
  return best;
}

namespace {

// (4.5): slip with r = r_N(theta) (1, mu cos, mu sin), u_N = 0; roots of
// g = u_T1 sin - u_T2 cos with u_T . s < 0, bracketed on a grid that includes the angles where
// the normal denominator vanishes, bisected, then polished by the local Newton.
void angleScan(const LocalContactData& d, const Eigen::Vector3d& qt, double mu,
               const LocalSolverSettings& s, LocalResult& best) {
  const Eigen::Matrix3d& W = d.W;
  const double a = W(0, 1), b = W(0, 2);
  auto denom = [&](double th) { return W(0, 0) + mu * (a * std::cos(th) + b * std::sin(th)); };
  auto point = [&](double th) {
    const double rN = -qt[0] / denom(th);
    return Eigen::Vector3d(rN, rN * mu * std::cos(th), rN * mu * std::sin(th));
  };
  auto g = [&](double th) {
    const Eigen::Vector3d u = W * point(th) + qt;
    return u[1] * std::sin(th) - u[2] * std::cos(th);
  };
  const double twoPi = 2.0 * std::numbers::pi;
  // The grid: scanAngles + 1 uniform angles merged with up to four angles beside the zeros of the
  // denominator (merged on the fly: this runs inside every bgs sweep and allocates nothing).
  std::array<double, 4> extra{};
  int extraCount = 0;
  const double R = std::hypot(a, b);
  if (mu * R > 0 && W(0, 0) <= mu * R) {  // denominator zero at phi +- acos(-W_NN / (mu R))
    const double phi = std::atan2(b, a), c = std::acos(std::clamp(-W(0, 0) / (mu * R), -1.0, 1.0));
    for (double th : {phi + c, phi - c})
      for (double eps : {-1e-12, 1e-12}) {
        double t = std::fmod(th + eps, twoPi);
        if (t < 0) t += twoPi;
        extra[static_cast<std::size_t>(extraCount++)] = t;
      }
  }
  for (int i = 1; i < extraCount; ++i)  // insertion sort of at most four angles
    for (int j = i;
         j > 0 && extra[static_cast<std::size_t>(j)] < extra[static_cast<std::size_t>(j - 1)]; --j)
      std::swap(extra[static_cast<std::size_t>(j)], extra[static_cast<std::size_t>(j - 1)]);
  const int gridSize = s.scanAngles + 1 + extraCount;
  int nextUniform = 0, nextExtra = 0;
  const auto nextAngle = [&] {
    const double uniform = nextUniform <= s.scanAngles ? twoPi * nextUniform / s.scanAngles
                                                       : std::numeric_limits<double>::infinity();
    if (nextExtra < extraCount && extra[static_cast<std::size_t>(nextExtra)] < uniform)
      return extra[static_cast<std::size_t>(nextExtra++)];
    ++nextUniform;
    return uniform;
  };
  double hiAngle = nextAngle();
  for (int k = 0; k + 1 < gridSize; ++k) {
    double lo = hiAngle, hi = nextAngle();
    hiAngle = hi;
    if (!(denom(lo) > 0 && denom(hi) > 0 && denom(0.5 * (lo + hi)) > 0)) continue;
    double glo = g(lo);
    const double ghi = g(hi);
    if (!(glo * ghi <= 0)) continue;
    for (int it = 0; it < 100 && hi - lo > 1e-16 * twoPi; ++it) {
      const double mid = 0.5 * (lo + hi), gm = g(mid);
      if ((gm <= 0) == (glo <= 0))
        lo = mid, glo = gm;
      else
        hi = mid;
    }
    const double th = 0.5 * (lo + hi);
    const Eigen::Vector3d r = point(th);
    const Eigen::Vector3d u = W * r + qt;
    if (!(u[1] * std::cos(th) + u[2] * std::sin(th) < 0)) continue;  // slip opposes u_T
    keepBetter(best, r, localError(d, qt, mu, r), LocalStage::AngleScan);
    const LocalResult polished = localNewton(d, qt, mu, r, s);
    keepBetter(best, polished.r, polished.error, LocalStage::AngleScan);
    if (best.error <= s.tolerance) return;
  }
}

// (3.3)-(3.4): projection iterations with a self-adaptive step.
Eigen::Vector3d projectionIterations(const LocalContactData& d, const Eigen::Vector3d& qt,
                                     double mu, Eigen::Vector3d r, int iterations) {
  double rho = d.rho;
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Vector3d u = d.W * r + qt;
    Eigen::Vector3d next, delta;
    for (int tries = 0; tries < 10; ++tries) {
      next = projectOntoCone(r - rho * deSaxceShift(u, mu), mu);
      delta = next - r;
      if (rho * (d.W * delta).norm() <= 0.9 * delta.norm()) break;
      rho *= 2.0 / 3.0;
    }
    if (rho * (d.W * delta).norm() < 0.3 * delta.norm()) rho *= 1.5;
    r = next;
  }
  return r;
}

}  // namespace

LocalResult solveLocalContact(const LocalContactData& d, const Eigen::Vector3d& qt, double mu,
                              const Eigen::Vector3d& incoming, const LocalSolverSettings& s) {
  if (qt[0] >= 0) return {Eigen::Vector3d::Zero(), 0.0, LocalStage::TakeOff};  // (4.2)
  if (mu == 0.0) {
    const double rN = d.W(0, 0) > 0 ? std::max(-qt[0] / d.W(0, 0), 0.0) : 0.0;
    const Eigen::Vector3d r(rN, 0.0, 0.0);
    return {r, localError(d, qt, mu, r), LocalStage::Frictionless};
  }
  if (d.invertible) {  // (4.3) stick: u = 0
    const Eigen::Vector3d r = -d.lu.solve(qt);
    if (r[0] > 0 && std::hypot(r[1], r[2]) <= mu * r[0]) return {r, 0.0, LocalStage::Stick};
  }
  LocalResult best{incoming, localError(d, qt, mu, incoming), LocalStage::Incoming};
  if (!std::isfinite(best.error)) best.error = std::numeric_limits<double>::infinity();
  const double qT = std::hypot(qt[1], qt[2]);
  if (qT > 0 && d.W(0, 0) > 0) {  // (4.4) slip for an isotropic block (else a start value)
    const double rN = -qt[0] / d.W(0, 0);
    const Eigen::Vector3d r(rN, -mu * rN * qt[1] / qT, -mu * rN * qt[2] / qT);
    keepBetter(best, r, localError(d, qt, mu, r), LocalStage::IsotropicSlip);
    if (best.error <= s.tolerance) return best;
  }
  const LocalResult newton = localNewton(d, qt, mu, best.r, s);
  keepBetter(best, newton.r, newton.error, LocalStage::Newton);
  if (best.error <= s.tolerance) return best;
  angleScan(d, qt, mu, s, best);
  if (best.error <= s.tolerance) return best;
  const Eigen::Vector3d projected = projectionIterations(d, qt, mu, best.r, s.projectionIterations);
  keepBetter(best, projected, localError(d, qt, mu, projected), LocalStage::Projection);
  const LocalResult polished = localNewton(d, qt, mu, projected, s);
  keepBetter(best, polished.r, polished.error, LocalStage::Projection);
  return best;
}

}  // namespace coulomb::solvers
