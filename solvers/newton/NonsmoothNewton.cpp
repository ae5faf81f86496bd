#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include <coulomb/solvers/newton/NewtonLinearSolver.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

namespace coulomb::solvers {

namespace {

// Phi and the blocks of A and B of every block of the problem.
class NewtonSystem {
 public:
  // Kept: rho and the Jacobian as the workspace holds them (newtonStepWithKeptFactors).
  NewtonSystem(const PreparedProblem& p, const NewtonFunction& f, NewtonWorkspace& work)
      : p_(p),
        f_(f),
        work_(work),
        rhoN_(work.rhoN),
        rhoT_(work.rhoT),
        jac_(work.jac),
        linear_(work.linear) {}

  NewtonSystem(const PreparedProblem& p, const NewtonFunction& f, const NewtonSettings& s,
               NewtonWorkspace& work)
      : NewtonSystem(p, f, work) {
    rhoN_.resize(p.blockCount());
    rhoT_.resize(p.blockCount());
    jac_.resize(p.blockCount());
    for (int b = 0; b < p.blockCount(); ++b) {
      if (!p.blocks[b].isContact()) {
        rhoN_[b] = rhoT_[b] = 1.0 / p.W.blockValues(p.W.diagonalBlock(b))[0];  // (10.2)
        continue;
      }
      const Eigen::Matrix3d W = p.contactBlock(b);
      switch (s.rho) {  // (5.14)
        case NewtonSettings::Rho::Spectral:
          rhoN_[b] = rhoT_[b] = inverseSpectralRadius(W);
          break;
        case NewtonSettings::Rho::SplitSpectral:
          rhoN_[b] = 1.0 / W(0, 0);
          rhoT_[b] = inverseTangentSpectralRadius(W);
          if (rhoT_[b] <= 0) rhoT_[b] = rhoN_[b];
          break;
        case NewtonSettings::Rho::Constant:
          rhoN_[b] = rhoT_[b] = s.constantRho;
          break;
      }
    }
  }

  // Phi(r) with u = W r + q given; stores A, B when `withJacobian`.
  void evaluate(const Eigen::VectorXd& r, const Eigen::VectorXd& u, Eigen::VectorXd& phi,
                bool withJacobian) {
    phi.resize(p_.size());
    Eigen::Vector3d ph;
    Eigen::Matrix3d A, B;
    for (int b = 0; b < p_.blockCount(); ++b) {
      const int o = p_.offset[b];
      const ConstraintBlock& blk = p_.blocks[b];
      if (blk.isContact()) {
        f_.contact(r.segment<3>(o), u.segment<3>(o), blk.mu, rhoN_[b], rhoT_[b], ph, A, B);
        phi.segment<3>(o) = ph;
        if (withJacobian) jac_[b] = {A, B};
      } else {
        double a = 0, bb = 0;
        f_.scalarRow(blk, r[o], u[o], rhoN_[b], phi[o], a, bb);
        if (withJacobian) {
          jac_[b].A.setZero();
          jac_[b].B.setZero();
          jac_[b].A(0, 0) = a;
          jac_[b].B(0, 0) = bb;
        }
      }
    }
  }

  // y = A x + B z (block diagonal products)
  void applyAB(const Eigen::VectorXd& x, const Eigen::VectorXd& z, Eigen::VectorXd& y) const {
    y.resize(p_.size());
    for (int b = 0; b < p_.blockCount(); ++b) {
      const int o = p_.offset[b], s = p_.W.blockSize(b);
      for (int a = 0; a < s; ++a) {
        double v = 0;
        for (int t = 0; t < s; ++t) v += jac_[b].A(a, t) * x[o + t] + jac_[b].B(a, t) * z[o + t];
        y[o + a] = v;
      }
    }
  }

  // g = J^T phi = W^T A^T phi + B^T phi (steepest-descent direction is -g); the workspace's.
  const Eigen::VectorXd& gradient(const Eigen::VectorXd& phi) {
    Eigen::VectorXd& atphi = work_.atphi;
    Eigen::VectorXd& g = work_.gradient;
    atphi.setZero(p_.size());
    g.setZero(p_.size());
    for (int b = 0; b < p_.blockCount(); ++b) {
      const int o = p_.offset[b], s = p_.W.blockSize(b);
      for (int a = 0; a < s; ++a)
        for (int t = 0; t < s; ++t) {
          atphi[o + t] += jac_[b].A(a, t) * phi[o + a];
          g[o + t] += jac_[b].B(a, t) * phi[o + a];
        }
    }
    p_.W.multiplyTransposeAdd(atphi, g);
    return g;
  }

  // Solves J_sigma d = -phi with eliminated unit rows (5.7); false if not accurate. With
  // `refactor` false, the rows kept and the factors of the last solve are reused.
  bool solve(const Eigen::VectorXd& phi, double sigma, Eigen::VectorXd& d, bool refactor = true) {
    const int n = p_.size();
    std::vector<int>& index = work_.index;
    std::vector<int>& kept = work_.kept;
    if (refactor) {
      index.assign(n, -1);
      kept.clear();
      kept.reserve(n);  // at most n rows kept: sized once, not regrown when R grows
    }
    d.setZero(n);
    for (int b = 0; b < p_.blockCount(); ++b) {
      const int o = p_.offset[b], s = p_.W.blockSize(b);
      for (int a = 0; a < s; ++a) {
        if (!refactor) {
          if (index[o + a] < 0) d[o + a] = -phi[o + a];
          continue;
        }
        bool unit = true;
        for (int t = 0; t < s && unit; ++t)
          unit = jac_[b].A(a, t) == 0.0 && jac_[b].B(a, t) == (t == a ? 1.0 : 0.0);
        if (unit) {
          d[o + a] = -phi[o + a];
        } else {
          index[o + a] = static_cast<int>(kept.size());
          kept.push_back(o + a);
        }
      }
    }
    const int m = static_cast<int>(kept.size());
    if (m == 0) return true;
    // rhs = -phi_R - (J_sigma d_E)_R
    Eigen::VectorXd& wd = work_.solveWd;
    Eigen::VectorXd& jd = work_.solveJd;
    if (m == n) {  // no row eliminated: d = 0, so J_sigma d = 0 (no product with W)
      jd.setZero(n);
    } else {
      wd = sigma * d;
      p_.W.multiplyAdd(d, wd);
      applyAB(wd, d, jd);
    }
    Eigen::VectorXd& rhs = work_.rhs;  // kept at the problem's size: |R| varies below it
    if (rhs.size() != n) rhs.resize(n);
    Eigen::VectorXd& x = work_.x;
    if (x.size() != n) x.resize(n);
    for (int k = 0; k < m; ++k) rhs[k] = -phi[kept[k]] - jd[kept[k]];
    // J_RR = (A (W + sigma I) + B)_RR: dense or sparse LU (NewtonLinearSolver).
    if (refactor ? !linear_.solveLeading(p_.W, p_.offset, jac_, kept, index, sigma, rhs, x)
                 : !linear_.solveAgain(rhs, x))
      return false;
    for (int k = 0; k < m; ++k) d[kept[k]] = x[k];
    return true;
  }

  double maxRho() const {
    double m = 0;
    for (double v : rhoN_) m = std::max(m, v);
    for (double v : rhoT_) m = std::max(m, v);
    return m;
  }

 private:
  const PreparedProblem& p_;
  const NewtonFunction& f_;
  NewtonWorkspace& work_;
  std::vector<double>&rhoN_, &rhoT_;
  std::vector<NewtonBlockJacobian>& jac_;
  NewtonLinearSolver& linear_;
};

}  // namespace

void runNonsmoothNewton(const PreparedProblem& p, const NewtonFunction& function,
                        const NewtonSettings& s, const SolveContext& context, int maxIterations,
                        Eigen::VectorXd& r, SolverReport& report, NewtonWorkspace* workspace) {
  const int n = p.size();
  std::optional<NewtonWorkspace> own;
  NewtonWorkspace& work = workspace != nullptr ? *workspace : own.emplace(s);
  work.factoredFor = nullptr;  // until a solve of this run factors its Jacobian
  NewtonSystem system(p, function, s, work);
  Eigen::VectorXd &u = work.u, &phi = work.phi, &d = work.d, &wd = work.wd, &jd = work.jd;
  Eigen::VectorXd &trialR = work.trialR, &trialU = work.trialU, &trialPhi = work.trialPhi;
  double e = 0.0, eAbsolute = 0.0;  // the common residual of r (relative, absolute)
  if (p.startEvaluatedAs(r)) {      // ContactSolver's start: its residual and u are known
    e = p.start.residual;
    eAbsolute = p.start.absolute;
    u = p.start.u;
  } else {
    e = p.residual(r, u, &eAbsolute);
  }
  Eigen::VectorXd& best = work.best;
  best = r;
  double bestE = e;
  std::vector<double>& bestHistory = work.bestHistory;
  bestHistory.reserve(static_cast<std::size_t>(std::max(maxIterations, 0)) + 1);  // no regrowth
  bestHistory.assign(1, bestE);
  // Watchdog (NewtonSettings::watchdogSteps): the point the relaxed full steps started from.
  const int watchdogSteps = s.watchdogSteps;
  const bool watchdog = watchdogSteps > 0;
  Eigen::VectorXd &watchR = work.watchR, &watchU = work.watchU;
  double watchE = 0.0, watchPsi = 0.0, watchSlope = 0.0;
  bool setWatch = true, searchNext = false;
  int relaxed = 0;
  double boost = 1.0;
  int failStreak = 0, steepest = 0;
  const double scaleRho = system.maxRho();
  report.nativeResidualName = "e_Phi = ||Phi|| / (||r|| + max rho ||q||) (5.13)";
  report.status = SolverStatus::MaxIterations;
  int k = 0;
  for (; k < maxIterations; ++k) {
    if (e <= context.tolerance()) {
      report.status = SolverStatus::Converged;
      break;
    }
    if (context.timeUp(report)) break;
    system.evaluate(r, u, phi, true);
    if (!phi.allFinite()) {
      report.status = SolverStatus::NumericalFailure;
      report.note("non-finite Phi");
      break;
    }
    report.nativeResidual = phi.norm() / (r.norm() + scaleRho * p.qNorm + 1e-300);
    const double psi0 = 0.5 * phi.squaredNorm();
    // (5.8) residual-scaled shift, escalated by x100 after failures.
    double sigma = std::clamp(e, s.minShift, s.maxShift) * p.maxDiagonal * boost;
    if (s.maxShift <= 0) sigma = 0;
    bool ok = system.solve(phi, sigma, d);
    if (!ok) {
      sigma = std::max(sigma, 1e-10 * p.maxDiagonal) * 100.0;
      ok = system.solve(phi, sigma, d);
    }
    report.maxRegularization = std::max(report.maxRegularization, sigma);
    work.factoredFor = ok ? &p : nullptr;
    work.factoredSigma = sigma;
    wd.setZero(n);
    if (ok) {
      p.W.multiplyAdd(d, wd);
      system.applyAB(wd, d, jd);
    }
    double slope = ok ? phi.dot(jd) : 0.0;
    if (!ok || !(slope < 0) || !d.allFinite()) {  // steepest descent on psi
      d = -system.gradient(phi);
      wd.setZero(n);
      p.W.multiplyAdd(d, wd);
      system.applyAB(wd, d, jd);
      slope = phi.dot(jd);
      ++steepest;
      if (!(slope < 0)) {
        report.status = SolverStatus::Stalled;
        report.note("no descent direction");
        break;
      }
    }
    // Armijo (5.11): the Facchinei-Pang safeguard replaces a too-flat Newton direction by the
    // steepest descent before the search.
    const bool armijo = s.lineSearch == NewtonSettings::LineSearch::Armijo;
    if (armijo && slope > -1e-8 * std::pow(d.norm(), 2.1)) {
      d = -system.gradient(phi);
      wd.setZero(n);
      p.W.multiplyAdd(d, wd);
      system.applyAB(wd, d, jd);
      slope = phi.dot(jd);
      ++steepest;
    }
    // Watchdog (Chamberlain, Powell, Lemarechal and Pedersen, Math. Prog. Study 16, 1982;
    // docs/solvers.md "Watchdog Newton"): a full step the search would cut (psi rising) is taken
    // as it is; the iterates must then come below the watchdog point (by armijoC x its slope)
    // within watchdogSteps steps, each making a new watchdog point, or the iteration returns to
    // it and takes the monotone search there.
    if (watchdog && setWatch) {
      watchR = r;
      watchU = u;
      watchE = e;
      watchPsi = psi0;
      watchSlope = slope;
      setWatch = false;
      relaxed = 0;
    }
    double alpha = 1.0, lo = 0.0, hi = std::numeric_limits<double>::infinity();
    double bestAlpha = 0.0, bestPsi = psi0;
    bool accepted = false;
    double fullStepPsi = std::numeric_limits<double>::quiet_NaN(), stepPsi = psi0;
    const bool tryFullStep = watchdog && !searchNext;
    if (tryFullStep) {
      trialR = r + d;
      trialU = u + wd;
      system.evaluate(trialR, trialU, trialPhi, false);
      fullStepPsi = 0.5 * trialPhi.squaredNorm();
      // Too long for the search (its acceptance test at alpha = 1 fails on the rising side):
      // taken as it is.
      if (fullStepPsi - psi0 > (armijo ? s.armijoC : s.m1) * slope) {
        accepted = true;
        stepPsi = fullStepPsi;
      }
    }
    // Goldstein-Price, Algorithm 5.2, or Armijo halving (5.11), from alpha = 1.
    for (int t = 0; t < s.lineSearchTrials && !accepted; ++t) {
      if (t > 0 || !tryFullStep) {
        trialR = r + alpha * d;
        trialU = u + alpha * wd;
        system.evaluate(trialR, trialU, trialPhi, false);
      }
      const double psi = t == 0 && tryFullStep ? fullStepPsi : 0.5 * trialPhi.squaredNorm();
      stepPsi = psi;
      if (psi < bestPsi) bestPsi = psi, bestAlpha = alpha;
      const double avg = (psi - psi0) / alpha;
      if (armijo) {
        if (psi <= psi0 + s.armijoC * alpha * slope) {
          accepted = true;
          break;
        }
        alpha *= 0.5;
        continue;
      }
      if (avg < s.m2 * slope) {
        lo = alpha;
      } else if (avg > s.m1 * slope) {
        hi = alpha;
      } else {
        accepted = true;
        break;
      }
      alpha = std::isfinite(hi) ? 0.5 * (lo + hi) : 10.0 * alpha;
    }
    if (!accepted) {
      ++report.lineSearchFailures;
      if (bestAlpha > 0) stepPsi = bestPsi;
      alpha = bestAlpha > 0 ? bestAlpha : alpha;
      if (++failStreak >= 3) {
        boost *= 100.0;
        failStreak = 0;
      }
    } else {
      failStreak = 0;
    }
    if (watchdog) {
      if (searchNext || stepPsi <= watchPsi + s.armijoC * watchSlope) {
        searchNext = false;  // progress (or the search from the watchdog point): a new one
        setWatch = true;
      } else if (++relaxed > watchdogSteps) {  // none in watchdogSteps steps: back, and search
        r = watchR;
        u = watchU;
        e = watchE;
        searchNext = true;
        continue;
      }
    }
    const double stepNorm = alpha * d.norm();
    r += alpha * d;
    e = p.residual(r, u, &eAbsolute);  // u recomputed: measured after the update
    if (!r.allFinite() || !std::isfinite(e)) {
      report.status = SolverStatus::NumericalFailure;
      report.note("non-finite iterate");
      r = best;
      e = bestE;
      ++k;
      break;
    }
    context.record(report, report.iterations + k + 1, e);
    if (e < bestE) {
      bestE = e;
      best = r;
    }
    bestHistory.push_back(bestE);
    if (e <= context.tolerance()) {
      report.status = SolverStatus::Converged;
      ++k;
      break;
    }
    const int h = static_cast<int>(bestHistory.size()) - 1;
    if (h >= s.stallIterations &&
        bestE > (1.0 - s.stallDecrease) * bestHistory[h - s.stallIterations]) {
      report.status = SolverStatus::Stalled;
      char msg[96];
      std::snprintf(msg, sizeof msg, "best residual fell by less than %g %% in %d iterations",
                    s.stallDecrease * 100, s.stallIterations);
      report.note(msg);
      ++k;
      break;
    }
    if (stepNorm <= 10 * std::numeric_limits<double>::epsilon() * r.norm()) {
      report.status = SolverStatus::Stalled;
      report.note("step below 10 eps ||r||");
      ++k;
      break;
    }
  }
  report.iterations += k;
  if (report.status == SolverStatus::Converged) {
    p.recordEnd(r, u, e, eAbsolute);  // u = W r + q of the answer, after the last update
  } else {
    r = best;
    work.factoredFor = nullptr;
  }
  if (steepest > 0) {
    char msg[48];
    std::snprintf(msg, sizeof msg, "%d steepest-descent steps", steepest);
    report.note(msg);
  }
}

bool newtonStepWithKeptFactors(const PreparedProblem& p, const NewtonFunction& function,
                               NewtonWorkspace& work, const Eigen::VectorXd& r,
                               const Eigen::VectorXd& uShifted, Eigen::VectorXd& out) {
  if (work.factoredFor != &p || r.size() != p.size() || uShifted.size() != p.size()) return false;
  NewtonSystem system(p, function, work);
  Eigen::VectorXd &phi = work.trialPhi, &d = work.d;
  // Phi alone: the workspace's A and B stay those the factors were built from.
  system.evaluate(r, uShifted, phi, /*withJacobian=*/false);
  if (!phi.allFinite() || !system.solve(phi, work.factoredSigma, d, /*refactor=*/false) ||
      !d.allFinite())
    return false;
  out = r + d;
  return true;
}

}  // namespace coulomb::solvers
