#include <coulomb/solvers/staggered/StaggeredSolver.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace coulomb::solvers {

namespace {

// One of the two QPs: the unknowns `rows` of r, the others frozen; min 1/2 x^T A x + b^T x over
// a product set, A = W(rows, rows), gradient A x + b = (W r + q)(rows).
class SubProblem {
 public:
  enum class Kind { Normal, Friction };
  SubProblem(const PreparedProblem& p, Kind kind) : p_(p), kind_(kind) {
    for (int b = 0; b < p.blockCount(); ++b) {
      const int o = p.offset[b];
      if (!p.blocks[b].isContact()) {
        if (kind == Kind::Normal) rows_.push_back(o), block_.push_back(b);
      } else if (kind == Kind::Normal) {
        rows_.push_back(o), block_.push_back(b);
      } else {
        rows_.push_back(o + 1), rows_.push_back(o + 2), block_.push_back(b), block_.push_back(b);
      }
    }
  }
  [[nodiscard]] int size() const { return static_cast<int>(rows_.size()); }

  Eigen::VectorXd gather(const Eigen::VectorXd& full) const {
    Eigen::VectorXd x(size());
    for (int i = 0; i < size(); ++i) x[i] = full[rows_[i]];
    return x;
  }
  void scatter(const Eigen::VectorXd& x, Eigen::VectorXd& full) const {
    for (int i = 0; i < size(); ++i) full[rows_[i]] = x[i];
  }
  // A x + b at x, the other unknowns of `r` frozen.
  Eigen::VectorXd gradient(const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
    scatter(x, r);
    Eigen::VectorXd u;
    p_.velocity(r, u);
    return gather(u);
  }
  // A d (d on the rows only).
  Eigen::VectorXd apply(const Eigen::VectorXd& d) const {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(p_.size()), out = Eigen::VectorXd::Zero(p_.size());
    scatter(d, full);
    p_.W().multiplyAdd(full, out);
    return gather(out);
  }
  // Projection on the product set; friction radii mu r_N from `r` (normals frozen).
  void project(Eigen::VectorXd& x, const Eigen::VectorXd& r) const {
    for (int i = 0; i < size(); ++i) {
      const ConstraintBlock& blk = p_.blocks[block_[i]];
      if (kind_ == Kind::Friction) {  // disks (2.5), two rows per contact
        const double radius = blk.mu * r[p_.offset[block_[i]]];
        const Eigen::Vector2d t = projectOntoDisk({x[i], x[i + 1]}, radius);
        x[i] = t[0], x[i + 1] = t[1];
        ++i;
        continue;
      }
      switch (blk.kind) {
        case BlockKind::Contact3D:
        case BlockKind::Unilateral:
          x[i] = std::max(x[i], 0.0);
          break;
        case BlockKind::Bounded:
          x[i] = std::clamp(x[i], blk.lower, blk.upper);
          break;
        case BlockKind::Equality:
          break;
      }
    }
  }
  // 1.1 lambda_max(sym A) by power iterations (8.3).
  double lipschitz(int iterations) const {
    Eigen::VectorXd v = Eigen::VectorXd::Ones(size()) / std::sqrt(std::max(1, size()));
    double lambda = 0;
    for (int k = 0; k < iterations; ++k) {
      Eigen::VectorXd w = apply(v);
      w = 0.5 * (w + applyTranspose(v));
      lambda = v.dot(w);
      const double n = w.norm();
      if (!(n > 0)) break;
      v = w / n;
    }
    return 1.1 * std::max(lambda, 1e-300);
  }

 private:
  Eigen::VectorXd applyTranspose(const Eigen::VectorXd& d) const {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(p_.size()), out = Eigen::VectorXd::Zero(p_.size());
    scatter(d, full);
    p_.W().multiplyTransposeAdd(full, out);
    return gather(out);
  }
  const PreparedProblem& p_;
  Kind kind_;
  std::vector<int> rows_, block_;
};

// Algorithm 8.2 on `sub` from the current r (its rows updated in place); returns iterations.
int apgd(const SubProblem& sub, const StaggeredOptions& o, double tolerance, Eigen::VectorXd& r) {
  if (sub.size() == 0) return 0;
  double L = sub.lipschitz(o.powerIterations);
  Eigen::VectorXd x = sub.gather(r);
  sub.project(x, r);
  Eigen::VectorXd y = x, best = x, work = r;
  double theta = 1.0, bestRes = std::numeric_limits<double>::infinity();
  int k = 0;
  for (; k < o.maxInner; ++k) {
    const Eigen::VectorXd g = sub.gradient(y, work);
    Eigen::VectorXd xn = y - g / L;
    sub.project(xn, r);
    for (int t = 0; t < 30; ++t) {  // (8.5)
      const Eigen::VectorXd d = xn - y;
      if (d.dot(sub.apply(d)) <= L * d.squaredNorm()) break;
      L *= 2.0;
      xn = y - g / L;
      sub.project(xn, r);
    }
    const double thetaNext = 0.5 * (-theta * theta + theta * std::sqrt(theta * theta + 4.0));
    const double beta = theta * (1.0 - theta) / (theta * theta + thetaNext);  // (8.6)
    Eigen::VectorXd yn = xn + beta * (xn - x);
    double thetaUse = thetaNext;
    if (o.restart && g.dot(xn - x) > 0) yn = xn, thetaUse = 1.0;  // (8.7)
    const Eigen::VectorXd gx = sub.gradient(xn, work);
    Eigen::VectorXd step = xn - gx / L;
    sub.project(step, r);
    const Eigen::VectorXd bvec = sub.gradient(Eigen::VectorXd::Zero(sub.size()), work);
    const double res = (xn - step).norm() / (xn.norm() + bvec.norm() / L + 1e-300);
    if (res < bestRes) bestRes = res, best = xn;
    x = xn;
    y = yn;
    theta = thetaUse;
    if (res <= tolerance) {
      ++k;
      break;
    }
    L *= 0.9;
  }
  sub.scatter(best, r);
  return k;
}

}  // namespace

void StaggeredSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                                    Eigen::VectorXd& r, SolverReport& report) const {
  const SubProblem normal(p, SubProblem::Kind::Normal), friction(p, SubProblem::Kind::Friction);
  const int maxOuter = context.maxIterations(options_.defaultMaxOuter);
  p.project(r);
  Eigen::VectorXd u, best = r;
  double e = p.residual(r, u), bestE = e;
  std::vector<double> bestHistory{bestE};
  long inner = 0;
  int k = 0;
  report.status = SolverStatus::MaxIterations;
  for (; k < maxOuter; ++k) {
    if (e <= context.tolerance()) {
      report.status = SolverStatus::Converged;
      break;
    }
    if (context.timeUp(report)) break;
    const double tau = std::max(context.tolerance() / 10, std::min(1e-3, e / 10));  // Alg. 8.1
    inner += apgd(normal, options_, tau, r);
    inner += apgd(friction, options_, tau, r);
    e = p.residual(r, u);
    if (!std::isfinite(e)) {
      report.status = SolverStatus::NumericalFailure;
      break;
    }
    context.record(report, k + 1, e);
    if (e < bestE) bestE = e, best = r;
    bestHistory.push_back(bestE);
    const int h = static_cast<int>(bestHistory.size()) - 1;
    if (h >= options_.stallWindow && bestE > 0.99 * bestHistory[h - options_.stallWindow]) {
      report.status = SolverStatus::Stalled;
      ++k;
      break;
    }
  }
  if (report.status == SolverStatus::Converged && e > context.tolerance())
    report.status = SolverStatus::Stalled;
  r = best;
  report.iterations = k;
  report.nativeResidual = bestE;
  report.nativeResidualName = "common e_rel of the best outer iterate";
  std::ostringstream msg;
  msg << "staggered: " << k << " outer iterations, " << inner << " APGD iterations";
  report.note(msg.str());
}

}  // namespace coulomb::solvers
