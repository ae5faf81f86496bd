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
        rhoN_[b] = rhoT_[b] = 1.0 / p.W().blockValues(p.W().diagonalBlock(b))[0];  // (10.2)
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
      const int o = p_.offset[b], s = p_.W().blockSize(b);
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
      const int o = p_.offset[b], s = p_.W().blockSize(b);
      for (int a = 0; a < s; ++a)
        for (int t = 0; t < s; ++t) {
          atphi[o + t] += jac_[b].A(a, t) * phi[o + a];
          g[o + t] += jac_[b].B(a, t) * phi[o + a];
        }
    }
    p_.W().multiplyTransposeAdd(atphi, g);
    return g;
  }

  // Solves J_sigma d = -phi with eliminated unit rows (5.7); false if not accurate. With
  // `refactor` false, the rows kept and the factors of the last solve are reused.
  bool solve(const Eigen::VectorXd& phi, double sigma, Eigen::VectorXd& d, bool refactor = true) {
    const int n = p_.size();
    work_.wdOfD = false;
    if (!refactor && work_.bodyFactored) return solveInBodySpace(phi, sigma, d, false);
    if (refactor) work_.bodyFactored = false;
    std::vector<int>& index = work_.index;
    std::vector<int>& kept = work_.kept;
    if (refactor) {
      index.assign(n, -1);
      kept.clear();
      kept.reserve(n);  // at most n rows kept: sized once, not regrown when R grows
    }
    d.setZero(n);
    for (int b = 0; b < p_.blockCount(); ++b) {
      const int o = p_.offset[b], s = p_.W().blockSize(b);
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
    if (refactor && prefersBodySpace(m, sigma) && solveInBodySpace(phi, sigma, d, true))
      return true;
    // rhs = -phi_R - (J_sigma d_E)_R
    Eigen::VectorXd& wd = work_.solveWd;
    Eigen::VectorXd& jd = work_.solveJd;
    if (m == n) {  // no row eliminated: d = 0, so J_sigma d = 0 (no product with W)
      jd.setZero(n);
    } else {
      wd = sigma * d;
      p_.W().multiplyAdd(d, wd);
      applyAB(wd, d, jd);
    }
    Eigen::VectorXd& rhs = work_.rhs;  // kept at the problem's size: |R| varies below it
    if (rhs.size() != n) rhs.resize(n);
    Eigen::VectorXd& x = work_.x;
    if (x.size() != n) x.resize(n);
    for (int k = 0; k < m; ++k) rhs[k] = -phi[kept[k]] - jd[kept[k]];
    // J_RR = (A (W + sigma I) + B)_RR: dense or sparse LU (NewtonLinearSolver).
    if (refactor ? !linear_.solveLeading(p_.W(), p_.offset, jac_, kept, index, sigma, rhs, x)
                 : !linear_.solveAgain(rhs, x))
      return false;
    for (int k = 0; k < m; ++k) d[kept[k]] = x[k];
    return true;
  }

  // The body-space path (BodySpaceNewtonSolve) when the problem keeps W's factors, J_sigma's
  // diagonal shift (sigma plus the subproblem's) is positive, the kept rows would take the dense
  // LU and the body-space factorization costs fewer flops.
  [[nodiscard]] bool prefersBodySpace(int keptRows, double sigma) {
    const BodySpaceDelassus* f = p_.factors.get();
    if (!(work_.bodySpaceSolve && f != nullptr && p_.scale.size() == 0 && f->size() == p_.size() &&
          sigma + p_.factorsShift > 0.0 && keptRows <= linear_.denseThreshold()))
      return false;
    if (eliminationFlops_ < 0.0) eliminationFlops_ = work_.body.eliminationFlops(*f);  // per run
    return work_.body.bodySpaceCost(*f, jac_, eliminationFlops_) <
           BodySpaceNewtonSolve::contactSpaceCost(keptRows);
  }

  // J_sigma d = -phi on every row in body space, refined on the residual (its W x through the
  // factors, not the Woodbury solve) while each step cuts it tenfold, at most 4 steps: the
  // body-space LU pivots only inside its 6 x 6 diagonal blocks and loses digits as the shift falls
  // (relative residual of one solve on a tower: 2e-10 at sigma = 1e-4 max W_ii, 2e-6 at 1e-6, 2e-2
  // at 1e-8), and each refinement step multiplies the residual by about that much again. True (and
  // d set) when the residual is within 1e-8 of the right-hand side, the contact-space LU's check.
  // With `refactor` false the factors of the last body-space solve are reused.
  bool solveInBodySpace(const Eigen::VectorXd& phi, double sigma, Eigen::VectorXd& d,
                        bool refactor) {
    BodySpaceNewtonSolve& body = work_.body;
    if (refactor) {
      work_.bodyFactored = false;
      if (!body.factor(*p_.factors, p_.offset, jac_, sigma + p_.factorsShift)) return false;
      ++work_.bodySpaceSolves;
    }
    Eigen::VectorXd &rhs = work_.bodyRhs, &x = work_.bodyX, &check = work_.bodyCheck;
    Eigen::VectorXd &wx = work_.wd, &shifted = work_.solveWd, &jd = work_.solveJd;
    rhs = -phi;
    body.solve(rhs, x);
    const double bound = 1e-8 * rhs.norm();
    double last = std::numeric_limits<double>::infinity();
    for (int refinement = 0;; ++refinement) {
      if (!x.allFinite()) return false;
      // W x, kept for the caller (wdOfD) when x is the answer; through the factors (J, M^-1 J^T:
      // fewer products than W's 3 x 3 blocks of every pair of contacts on a body).
      wx.setZero(p_.size());
      p_.factors->multiplyAdd(x, wx);
      if (p_.factorsShift != 0.0) wx += p_.factorsShift * x;
      shifted = wx + sigma * x;
      applyAB(shifted, x, jd);
      check = rhs - jd;
      const double residual = check.norm();
      if (residual <= bound) break;
      if (refinement == 4 || !(residual < 0.1 * last)) return false;
      last = residual;
      body.solve(check, jd);  // the correction (jd is free until the next product)
      x += jd;
    }
    d = x;
    work_.bodyFactored = true;
    work_.wdOfD = true;
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
  double eliminationFlops_ = -1.0;  // of the body-space LU, once per run (W's partition is fixed)
};

// The Newton direction at r (u = W r + q): Phi and its Jacobian, d from J_sigma d = -Phi with the
// residual-scaled shift (5.8), escalated by `boost` after failed searches; the steepest descent on
// psi where that gives no descent (and, under Armijo, where it is too flat: the Facchinei-Pang
// safeguard of (5.11)). On success: psi0 = psi(r), slope = Phi . J d < 0, wd = W d.
struct Direction {
  double psi0 = 0.0, slope = 0.0;
};

std::optional<Direction> newtonDirection(NewtonSystem& system, const PreparedProblem& p,
                                         const NewtonSettings& s, double e, double boost,
                                         double scaleRho, NewtonWorkspace& work,
                                         const Eigen::VectorXd& r, SolverReport& report,
                                         int& steepest) {
  const int n = p.size();
  Eigen::VectorXd &u = work.u, &phi = work.phi, &d = work.d, &wd = work.wd, &jd = work.jd;
  system.evaluate(r, u, phi, true);
  if (!phi.allFinite()) {
    report.status = SolverStatus::NumericalFailure;
    report.note("non-finite Phi");
    return std::nullopt;
  }
  report.nativeResidual = phi.norm() / (r.norm() + scaleRho * p.qNorm + 1e-300);
  Direction out;
  out.psi0 = 0.5 * phi.squaredNorm();
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
  const auto steepestDescent = [&] {
    d = -system.gradient(phi);
    wd.setZero(n);
    p.W().multiplyAdd(d, wd);
    system.applyAB(wd, d, jd);
    out.slope = phi.dot(jd);
    ++steepest;
  };
  if (!ok || !work.wdOfD) {  // the body-space solve leaves W d in wd (its residual check)
    wd.setZero(n);
    if (ok) p.W().multiplyAdd(d, wd);
  }
  if (ok) {
    system.applyAB(wd, d, jd);
    out.slope = phi.dot(jd);
  }
  if (!ok || !(out.slope < 0) || !d.allFinite()) {
    steepestDescent();
    if (!(out.slope < 0)) {
      report.status = SolverStatus::Stalled;
      report.note("no descent direction");
      return std::nullopt;
    }
  }
  if (s.lineSearch == NewtonSettings::LineSearch::Armijo &&
      out.slope > -1e-8 * std::pow(d.norm(), 2.1))
    steepestDescent();
  return out;
}

// The search along d from r: Goldstein-Price (Algorithm 5.2) or Armijo halving (5.11), from
// alpha = 1, whose psi is `fullStepPsi` when the watchdog evaluated it already (NaN otherwise).
// Not accepted: the best alpha tried (or the last) and its psi.
struct SearchResult {
  double alpha = 1.0, psi = 0.0;
  bool accepted = false;
};

SearchResult lineSearch(NewtonSystem& system, const NewtonSettings& s, NewtonWorkspace& work,
                        const Eigen::VectorXd& r, const Direction& at, double fullStepPsi) {
  const Eigen::VectorXd &u = work.u, &d = work.d, &wd = work.wd;
  Eigen::VectorXd &trialR = work.trialR, &trialU = work.trialU, &trialPhi = work.trialPhi;
  const bool armijo = s.lineSearch == NewtonSettings::LineSearch::Armijo;
  SearchResult out;
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  double bestAlpha = 0.0, bestPsi = at.psi0;
  for (int t = 0; t < s.lineSearchTrials; ++t) {
    double psi = fullStepPsi;
    if (t > 0 || std::isnan(fullStepPsi)) {
      trialR = r + out.alpha * d;
      trialU = u + out.alpha * wd;
      system.evaluate(trialR, trialU, trialPhi, false);
      psi = 0.5 * trialPhi.squaredNorm();
    }
    out.psi = psi;
    if (psi < bestPsi) bestPsi = psi, bestAlpha = out.alpha;
    if (armijo) {
      if (psi <= at.psi0 + s.armijoC * out.alpha * at.slope) {
        out.accepted = true;
        return out;
      }
      out.alpha *= 0.5;
      continue;
    }
    const double avg = (psi - at.psi0) / out.alpha;
    if (avg < s.m2 * at.slope) {
      lo = out.alpha;
    } else if (avg > s.m1 * at.slope) {
      hi = out.alpha;
    } else {
      out.accepted = true;
      return out;
    }
    out.alpha = std::isfinite(hi) ? 0.5 * (lo + hi) : 10.0 * out.alpha;
  }
  if (bestAlpha > 0) out.alpha = bestAlpha, out.psi = bestPsi;
  return out;
}

enum class Stall { None, Flat, TooSlow };

// Stall test (5.12) on the best residual of the last s.stallIterations iterations: it fell by less
// than s.stallDecrease (flat), or it falls at a rate that, kept up, would not reach the tolerance
// within the iterations left (too slow: a watchdog cycle that gains 2 % per return, as on
// box_pile_1000's first impacts, would use the whole budget and end far from the tolerance; the
// caller's fallback, the proximal loop, gets the iterations instead).
Stall stallOf(const std::vector<double>& bestHistory, const NewtonSettings& s, double tolerance,
              int iterationsLeft) {
  const int h = static_cast<int>(bestHistory.size()) - 1;
  if (h < s.stallIterations) return Stall::None;
  const double before = bestHistory[h - s.stallIterations], best = bestHistory[h];
  if (best > (1.0 - s.stallDecrease) * before) return Stall::Flat;
  if (!(tolerance > 0.0) || best <= tolerance) return Stall::None;
  const double needed = s.stallIterations * std::log(tolerance / best) / std::log(best / before);
  return needed > iterationsLeft ? Stall::TooSlow : Stall::None;
}

}  // namespace

void runNonsmoothNewton(const PreparedProblem& p, const NewtonFunction& function,
                        const NewtonSettings& s, const SolveContext& context, int maxIterations,
                        Eigen::VectorXd& r, SolverReport& report, NewtonWorkspace* workspace) {
  std::optional<NewtonWorkspace> own;
  NewtonWorkspace& work = workspace != nullptr ? *workspace : own.emplace(s);
  work.factoredFor = nullptr;  // until a solve of this run factors its Jacobian
  NewtonSystem system(p, function, s, work);
  Eigen::VectorXd &u = work.u, &d = work.d, &wd = work.wd;
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
  // Watchdog (NewtonSettings::watchdogSteps): the point the relaxed full steps started from, with
  // its direction, which the search takes from there on a return.
  const bool watchdog = s.watchdogSteps > 0;
  Eigen::VectorXd &watchR = work.watchR, &watchU = work.watchU;
  Eigen::VectorXd &watchD = work.watchD, &watchWd = work.watchWd;
  double watchE = 0.0;
  Direction watch;
  bool setWatch = true, searchNext = false;
  int relaxed = 0;
  double boost = 1.0;
  int failStreak = 0, steepest = 0, returns = 0;
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
    Direction at;
    if (searchNext) {  // back at the watchdog point: its direction again
      at = watch;
      d = watchD;
      wd = watchWd;
      work.factoredFor = nullptr;  // the factors are of a later iterate
    } else if (const std::optional<Direction> found =
                   newtonDirection(system, p, s, e, boost, scaleRho, work, r, report, steepest)) {
      at = *found;
    } else {
      break;
    }
    // Watchdog (Chamberlain, Powell, Lemarechal and Pedersen, Math. Prog. Study 16, 1982;
    // docs/solvers.md "Watchdog Newton"): a full step the search would cut (psi rising) is taken
    // as it is; the iterates must then come below the watchdog point (by armijoC x its slope)
    // within watchdogSteps steps, each making a new watchdog point, or the iteration returns to
    // it and takes the monotone search there.
    if (watchdog && setWatch) {
      watchR = r;
      watchU = u;
      watchD = d;
      watchWd = wd;
      watchE = e;
      watch = at;
      setWatch = false;
      relaxed = 0;
    }
    SearchResult step;
    double fullStepPsi = std::numeric_limits<double>::quiet_NaN();
    if (watchdog && !searchNext) {
      trialR = r + d;
      trialU = u + wd;
      system.evaluate(trialR, trialU, trialPhi, false);
      fullStepPsi = 0.5 * trialPhi.squaredNorm();
      // Too long for the search (its acceptance test at alpha = 1 fails on the rising side):
      // taken as it is.
      const bool armijo = s.lineSearch == NewtonSettings::LineSearch::Armijo;
      if (fullStepPsi - at.psi0 > (armijo ? s.armijoC : s.m1) * at.slope)
        step = {1.0, fullStepPsi, true};
    }
    if (!step.accepted) step = lineSearch(system, s, work, r, at, fullStepPsi);
    if (!step.accepted) {
      ++report.lineSearchFailures;
      if (++failStreak >= 3) {
        boost *= 100.0;
        failStreak = 0;
      }
    } else {
      failStreak = 0;
    }
    if (watchdog) {
      if (searchNext || step.psi <= watch.psi0 + s.armijoC * watch.slope) {
        searchNext = false;  // progress (or the search from the watchdog point): a new one
        setWatch = true;
      } else if (++relaxed > s.watchdogSteps) {  // none in watchdogSteps steps: back, and search
        r = watchR;
        u = watchU;
        e = watchE;
        searchNext = true;
        ++returns;
        if (s.watchdogReturnStalls) {
          report.status = SolverStatus::Stalled;
          report.note("watchdog return: handed over");
          ++k;
          break;
        }
        continue;
      }
    }
    const double stepNorm = step.alpha * d.norm();
    r += step.alpha * d;
    // u = W r + q follows r through W d (known from the direction), saving a product with W per
    // iteration; its round-off (about eps ||W d|| per step) is far below any tolerance, and a
    // converged verdict is confirmed with u recomputed from r.
    u += step.alpha * wd;
    e = p.residualFromVelocity(r, u, &eAbsolute);
    if (e <= context.tolerance()) e = p.residual(r, u, &eAbsolute);
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
    if (const Stall stall = stallOf(bestHistory, s, context.tolerance(), maxIterations - k - 1);
        stall != Stall::None) {
      report.status = SolverStatus::Stalled;
      char msg[96];
      if (stall == Stall::Flat)
        std::snprintf(msg, sizeof msg, "best residual fell by less than %g %% in %d iterations",
                      s.stallDecrease * 100, s.stallIterations);
      else
        std::snprintf(msg, sizeof msg,
                      "best residual falls too slowly to reach the tolerance in %d iterations",
                      maxIterations - k - 1);
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
  if (returns > 0) {
    char msg[48];
    std::snprintf(msg, sizeof msg, "%d returns to the watchdog point", returns);
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
