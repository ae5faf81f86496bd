#include <coulomb/solvers/GaussSeidelLoop.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <vector>

namespace coulomb::solvers {

namespace {

// Local free velocity of block b (3.1): q_b + sum over the other blocks of its row.
void localFreeVelocity(const PreparedProblem& p, int b, const Eigen::VectorXd& r, double* qt) {
  const BlockSparseMatrix& W = p.W;
  const int off = p.offset[b], s = W.blockSize(b);
  for (int a = 0; a < s; ++a) qt[a] = p.q[off + a];
  for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
    const int j = W.blockColumn(k);
    if (j == b) continue;
    const double* v = W.blockValues(k);
    const int oj = p.offset[j], sj = W.blockSize(j);
    if (s == 3 && sj == 3) {
      const double x0 = r[oj], x1 = r[oj + 1], x2 = r[oj + 2];
      qt[0] += v[0] * x0 + v[1] * x1 + v[2] * x2;
      qt[1] += v[3] * x0 + v[4] * x1 + v[5] * x2;
      qt[2] += v[6] * x0 + v[7] * x1 + v[8] * x2;
    } else {
      for (int a = 0; a < s; ++a)
        for (int c = 0; c < sj; ++c) qt[a] += v[sj * a + c] * r[oj + c];
    }
  }
}

// The same in body space (BodySpaceDelassus): q_b + J_b dv - W_bb r_b with dv = M^-1 J^T r, so
// O(1) per block instead of one product per block sharing a body.
void bodySpaceFreeVelocity(const PreparedProblem& p, int b, const Eigen::VectorXd& r,
                           const Eigen::VectorXd& dv, double* qt) {
  const int off = p.offset[b], s = p.blocks[b].size();
  for (int a = 0; a < s; ++a) qt[a] = p.q[off + a];
  p.bodySpace->addBlockVelocity(b, dv, qt);
  const double* d = p.diagonalBlock(b);
  for (int a = 0; a < s; ++a)
    for (int c = 0; c < s; ++c) qt[a] -= d[s * a + c] * r[off + c];
}

double projectScalar(const ConstraintBlock& b, double x) {
  switch (b.kind) {
    case BlockKind::Unilateral:
      return std::max(x, 0.0);
    case BlockKind::Bounded:
      return std::clamp(x, b.lower, b.upper);
    default:
      return x;
  }
}

}  // namespace

void runGaussSeidel(const PreparedProblem& p, const SolveContext& context,
                    const GaussSeidelSettings& settings, const ContactUpdate& update,
                    Eigen::VectorXd& r, SolverReport& report, GaussSeidelWorkspace* workspace) {
  GaussSeidelWorkspace local;
  GaussSeidelWorkspace& work = workspace != nullptr ? *workspace : local;
  const int nb = p.blockCount();
  const int maxSweeps = context.maxIterations(settings.defaultMaxSweeps);
  std::vector<int>& order = work.order;
  order.resize(nb);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(settings.seed);
  double omega = settings.omega;
  bool omegaSwitched = false;

  Eigen::VectorXd &u = work.u, &best = work.best;
  best = r;
  const BodySpaceDelassus* body = p.bodySpace.get();
  Eigen::VectorXd& dv = work.dv;  // body space: M^-1 J^T r, kept current by every block update
  double bestResidual = 0.0;
  if (p.startIs(r)) {  // ContactSolver::solve's start: its residual and dv are known
    bestResidual = p.start.residual;
    if (body) dv = p.start.dv;
  } else if (body) {  // dv once for both the start's residual and the sweeps (what multiplyAdd
                      // does)
    body->bodyVelocities(r, dv);
    u = p.q;
    for (int b = 0; b < nb; ++b) body->addBlockVelocity(b, dv, u.data() + p.offset[b]);
    bestResidual = p.residualFromVelocity(r, u);
  } else {
    bestResidual = p.residual(r, u);
  }
  // The options' window shortens the solver's own (SolverOptions::stallWindow).
  const int stallWindow = context.options().stallWindow > 0
                              ? std::min(context.options().stallWindow, settings.stallWindow)
                              : settings.stallWindow;
  double windowBest = bestResidual;
  int windowStart = 0;
  report.status = SolverStatus::MaxIterations;
  report.nativeResidualName = "common residual at the last check";
  int sweep = 0;
  const bool cg = settings.conjugateGradient;
  Eigen::VectorXd &previous = work.previous, &direction = work.direction;
  Eigen::VectorXd &previousDv = work.previousDv, &directionDv = work.directionDv;
  double previousStepNorm = -1.0;  // ||x_k - x_{k-1}||^2 of the last sweep; < 0: no direction yet
  while (sweep < maxSweeps) {
    if (context.timeUp(report)) break;
    ++sweep;
    if (cg) {
      previous = r;
      if (body) previousDv = dv;
    }
    if (settings.shuffle)
      for (int i = nb - 1; i > 0; --i) std::swap(order[i], order[rng() % (i + 1)]);
    for (int b : order) {
      const int off = p.offset[b];
      double qt[3], before[3] = {r[off], 0.0, 0.0};
      if (body) {
        bodySpaceFreeVelocity(p, b, r, dv, qt);
        if (p.blocks[b].isContact()) before[1] = r[off + 1], before[2] = r[off + 2];
      } else {
        localFreeVelocity(p, b, r, qt);
      }
      const ConstraintBlock& blk = p.blocks[b];
      if (blk.isContact()) {
        const Eigen::Vector3d old(r[off], r[off + 1], r[off + 2]);
        Eigen::Vector3d next = old;
        update(b, Eigen::Vector3d(qt[0], qt[1], qt[2]), next);
        if (omega != 1.0) {  // relax the step, then project (3.5)
          double x[3] = {old[0] + omega * (next[0] - old[0]), old[1] + omega * (next[1] - old[1]),
                         old[2] + omega * (next[2] - old[2])};
          projectOntoConeSweep(x, blk.mu);
          next = Eigen::Vector3d(x[0], x[1], x[2]);
        }
        if (next.allFinite()) r.segment<3>(off) = next;
      } else {  // exact scalar solve: u_i = W_ii r_i + q~_i = 0, then project (10.1)
        const double w = p.diagonalBlock(b)[0];
        const double exact = projectScalar(blk, -qt[0] / w);
        r[off] = projectScalar(blk, r[off] + omega * (exact - r[off]));
      }
      if (body) {
        const double dx[3] = {r[off] - before[0], blk.isContact() ? r[off + 1] - before[1] : 0.0,
                              blk.isContact() ? r[off + 2] - before[2] : 0.0};
        body->addBlockImpulse(b, dx, dv);
      }
    }
    // NNCG: the sweep's step g = x_{k+1} - x_k plays -grad f; beta = ||g_{k+1}||^2/||g_k||^2.
    double beta = 0.0;
    if (cg) {
      const double stepNorm = (r - previous).squaredNorm();
      if (previousStepNorm > 0) beta = stepNorm / previousStepNorm;
      if (!(beta <= 1.0)) beta = 0.0;  // restart: p = 0
      previousStepNorm = stepNorm;
    }
    auto accelerate = [&] {  // x += beta p, then p = x_new - x_old (= beta p + g); p = 0 on restart
      if (!cg) return;
      if (beta > 0) {
        r += beta * direction;
        if (body) dv += beta * directionDv;
      }
      if (beta == 0.0 && sweep > 1) {
        direction.setZero(r.size());
        if (body) directionDv.setZero(dv.size());
      } else {
        direction = r - previous;
        if (body) directionDv = dv - previousDv;
      }
    };
    const int interval =
        settings.residualInterval > 0 ? settings.residualInterval : std::clamp(sweep / 20, 1, 5);
    if (sweep % interval != 0 && sweep != maxSweeps) {
      accelerate();
      continue;
    }
    double e = 0.0;
    if (body) {  // u = q + J dv: one pass, dv is current
      u = p.q;
      for (int b = 0; b < nb; ++b) body->addBlockVelocity(b, dv, u.data() + p.offset[b]);
      e = p.sweepResidualFromVelocity(r, u);
    } else {
      p.velocity(r, u);
      e = p.sweepResidualFromVelocity(r, u);
    }
    context.record(report, sweep, e);
    report.nativeResidual = e;
    if (e < bestResidual || !std::isfinite(bestResidual)) {
      bestResidual = e;
      best = r;
    }
    if (e <= context.tolerance()) {
      report.status = SolverStatus::Converged;
      break;
    }
    if (!std::isfinite(e)) {
      report.status = SolverStatus::NumericalFailure;
      report.note("non-finite residual");
      break;
    }
    if (sweep - windowStart >= stallWindow) {
      if (bestResidual > (1.0 - settings.stallDecrease) * windowBest) {
        if (settings.omegaAfterStall > 0 && !omegaSwitched) {
          omegaSwitched = true;
          omega = settings.omegaAfterStall;
          std::ostringstream s;
          s << "stalled at sweep " << sweep << " (" << bestResidual << "): omega -> " << omega;
          report.note(s.str());
          r = best;
          if (body) body->bodyVelocities(r, dv);
          beta = 0.0;  // no momentum across the reset
          previousStepNorm = -1.0;
        } else {
          report.status = SolverStatus::Stalled;
          std::ostringstream s;
          s << "best residual fell by less than " << settings.stallDecrease * 100 << " % in "
            << stallWindow << " sweeps";
          report.note(s.str());
          break;
        }
      }
      windowBest = bestResidual;
      windowStart = sweep;
    }
    accelerate();
  }
  report.iterations = sweep;
  if (report.status != SolverStatus::Converged) r = best;
  if (report.timeLimitReached) report.note("time limit reached");
}

}  // namespace coulomb::solvers
