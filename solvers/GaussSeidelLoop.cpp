#include <coulomb/solvers/GaussSeidelLoop.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/ParallelLoop.hpp>
#include <coulomb/solvers/Residual.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>
#include <vector>

namespace coulomb::solvers {

namespace {

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

// Boundary blocks of one colour per task: a block costs 50-200 ns, so a task of 128 is long
// against the task system's hand-over (about a microsecond) yet splits a colour of a few hundred
// blocks over two threads. How a colour is cut never changes the result (its blocks are
// independent).
constexpr int kBlocksPerTask = 128;
constexpr int kBlocksPerCheck = 1024;            // a piece of a residual check: ~40 ns per block
constexpr Eigen::Index kEntriesPerPiece = 8192;  // a piece of the loop's vector work

// The split sweep's copies (GaussSeidelWorkspace::blocks, sweepFactors) in the order's order.
void gatherSweep(const PreparedProblem& p, const std::vector<int>& order,
                 GaussSeidelWorkspace& work) {
  const int nb = static_cast<int>(order.size());
  p.bodySpace->gather(order.data(), nb, work.sweepFactors);
  work.blocks.resize(nb);
  for (int i = 0; i < nb; ++i) {
    const int b = order[i], k = p.blocks[b].size();
    SweepBlock& copy = work.blocks[i];
    copy.block = b;
    copy.offset = p.offset[b];
    copy.contact = p.blocks[b].isContact();
    copy.mu = p.blocks[b].mu;
    for (int a = 0; a < k; ++a) copy.q[a] = p.q[copy.offset + a];
    std::copy_n(p.diagonalBlock(b), k * k, copy.diagonal);
  }
}

}  // namespace

void localFreeVelocity(const PreparedProblem& p, int b, const Eigen::VectorXd& r, double* qt) {
  const BlockSparseMatrix& W = p.W();
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

void runGaussSeidel(const PreparedProblem& p, const SolveContext& context,
                    const GaussSeidelSettings& settings, const ContactUpdate& update,
                    Eigen::VectorXd& r, SolverReport& report, GaussSeidelWorkspace* workspace) {
  std::optional<GaussSeidelWorkspace> local;  // only without the solver's (it allocates)
  GaussSeidelWorkspace& work = workspace != nullptr ? *workspace : local.emplace();
  const int nb = p.blockCount();
  const int maxSweeps = context.maxIterations(settings.defaultMaxSweeps);
  // Split sweeps (SolverOptions::sweepPartBlocks, SweepPartition.hpp): the parts' interiors,
  // then the boundary colour by colour; segment s of the order is [segmentBegin(s),
  // segmentBegin(s + 1)), the parts first. The shuffle permutes within each segment only.
  const int parts = SweepPartition::partsFor(nb, context.options().sweepPartBlocks);
  const bool split = parts >= 2;
  std::vector<int>& order = work.order;
  SweepPartition& partition = work.partition;
  if (split) {
    partition.build(p, parts);
    order = partition.order();
  } else {
    order.resize(nb);
    std::iota(order.begin(), order.end(), 0);
  }
  const int segments = split ? parts + partition.colours() : 1;
  auto segmentBegin = [&](int s) {
    if (!split) return s == 0 ? 0 : nb;
    return s <= parts ? partition.partStart(s) : partition.colourStart(s - parts);
  };
  ParallelLoop* parallel = context.options().parallel;
  if (!split || (parallel != nullptr && parallel->threads() < 2)) parallel = nullptr;
  std::mt19937_64 rng(settings.seed);
  double omega = settings.omega;
  bool omegaSwitched = false;

  Eigen::VectorXd &u = work.u, &best = work.best;
  best = r;
  const BodySpaceDelassus* body = p.bodySpace.get();
  // A split sweep visits the blocks in another order than their storage: what a visit reads is
  // copied once per solve in the sweep's order, so that the sweep streams it (on a 25 000-contact
  // packing the scattered reads cost 40-60 % more per sweep than the block order's).
  const bool gathered = body != nullptr && split && !settings.shuffle;
  if (gathered) gatherSweep(p, order, work);
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
  if (cg) {  // sized on every call, not on the first momentum step: a steady step allocates nothing
    previous.resize(r.size());
    direction.resize(r.size());
    if (body) {
      previousDv.resize(dv.size());
      directionDv.resize(dv.size());
    }
  }
  // A split sweep spreads the loop's vector work over the threads too: element by element, and
  // sums in fixed pieces added in order, so that the bits do not depend on the threads. (An
  // unsplit sweep keeps its plain expressions: its results stay those of the block order.)
  auto forPieces = [&](Eigen::Index size, Eigen::Index pieceSize, auto&& piece) {
    const auto pieces = static_cast<std::size_t>((size + pieceSize - 1) / pieceSize);
    auto task = [&](std::size_t k) {
      const Eigen::Index begin = static_cast<Eigen::Index>(k) * pieceSize;
      piece(k, begin, std::min(size, begin + pieceSize));
    };
    if (parallel != nullptr && pieces > 1)
      parallel->forEach(pieces, IndexTask(task));
    else
      for (std::size_t k = 0; k < pieces; ++k) task(k);
    return pieces;
  };
  auto assign = [&](Eigen::VectorXd& to, const auto& expression) {  // to = expression, in pieces
    to.resize(expression.size());
    forPieces(to.size(), kEntriesPerPiece, [&](std::size_t, Eigen::Index b, Eigen::Index e) {
      to.segment(b, e - b) = expression.segment(b, e - b);
    });
  };
  std::vector<double>& sums = work.pieceSums;
  auto sumPieces = [&](std::size_t pieces) {
    double total = 0.0;
    for (std::size_t k = 0; k < pieces; ++k) total += sums[k];
    return total;
  };
  while (sweep < maxSweeps) {
    if (context.timeUp(report)) break;
    ++sweep;
    if (cg && split) {
      assign(previous, r);
      if (body) assign(previousDv, dv);
    } else if (cg) {
      previous = r;
      if (body) previousDv = dv;
    }
    if (settings.shuffle)
      for (int segment = 0; segment < segments; ++segment) {
        const int first = segmentBegin(segment);
        for (int i = segmentBegin(segment + 1) - first - 1; i > 0; --i)
          std::swap(order[first + i], order[first + rng() % (i + 1)]);
      }
    auto visit = [&](int i) {  // the block at position i of the order
      const SweepBlock* copy = gathered ? &work.blocks[i] : nullptr;
      const int b = copy ? copy->block : order[i];
      const ConstraintBlock& blk = p.blocks[b];  // read for scalar rows only when gathered
      const bool contact = copy ? copy->contact : blk.isContact();
      const int off = copy ? copy->offset : p.offset[b];
      double qt[3], before[3] = {r[off], 0.0, 0.0};
      if (copy) {  // q~ = q + J dv - W_bb r from the copies (bodySpaceFreeVelocity)
        const int k = contact ? 3 : 1;
        for (int a = 0; a < k; ++a) qt[a] = copy->q[a];
        work.sweepFactors.addBlockVelocity(i, dv, qt);
        for (int a = 0; a < k; ++a)
          for (int c = 0; c < k; ++c) qt[a] -= copy->diagonal[k * a + c] * r[off + c];
      } else if (body) {
        bodySpaceFreeVelocity(p, b, r, dv, qt);
      } else {
        localFreeVelocity(p, b, r, qt);
      }
      if (contact) {
        before[1] = r[off + 1], before[2] = r[off + 2];
        const Eigen::Vector3d old(r[off], r[off + 1], r[off + 2]);
        Eigen::Vector3d next = old;
        update(b, Eigen::Vector3d(qt[0], qt[1], qt[2]), next);
        if (omega != 1.0) {  // relax the step, then project (3.5)
          double x[3] = {old[0] + omega * (next[0] - old[0]), old[1] + omega * (next[1] - old[1]),
                         old[2] + omega * (next[2] - old[2])};
          projectOntoCone(x, copy ? copy->mu : blk.mu);
          next = Eigen::Vector3d(x[0], x[1], x[2]);
        }
        if (next.allFinite()) r.segment<3>(off) = next;
      } else {  // exact scalar solve: u_i = W_ii r_i + q~_i = 0, then project (10.1)
        const double w = copy ? copy->diagonal[0] : p.diagonalBlock(b)[0];
        const double exact = projectScalar(blk, -qt[0] / w);
        r[off] = projectScalar(blk, r[off] + omega * (exact - r[off]));
      }
      if (body) {
        const double dx[3] = {r[off] - before[0], contact ? r[off + 1] - before[1] : 0.0,
                              contact ? r[off + 2] - before[2] : 0.0};
        if (copy)
          work.sweepFactors.addBlockImpulse(i, dx, dv);
        else
          body->addBlockImpulse(b, dx, dv);
      }
    };
    auto sweepSegment = [&](int segment) {
      for (int i = segmentBegin(segment); i < segmentBegin(segment + 1); ++i) visit(i);
    };
    if (parallel == nullptr) {  // the same order on the calling thread
      for (int segment = 0; segment < segments; ++segment) sweepSegment(segment);
    } else {
      auto part = [&](std::size_t k) { sweepSegment(static_cast<int>(k)); };
      parallel->forEach(static_cast<std::size_t>(parts), IndexTask(part));
      for (int segment = parts; segment < segments; ++segment) {  // the boundary's colours
        const int first = segmentBegin(segment), count = segmentBegin(segment + 1) - first;
        if (count < 2 * kBlocksPerTask) {
          sweepSegment(segment);
          continue;
        }
        auto chunk = [&](std::size_t task) {
          const int begin = first + static_cast<int>(task) * kBlocksPerTask;
          const int end = std::min(begin + kBlocksPerTask, first + count);
          for (int i = begin; i < end; ++i) visit(i);
        };
        parallel->forEach(static_cast<std::size_t>((count + kBlocksPerTask - 1) / kBlocksPerTask),
                          IndexTask(chunk));
      }
    }
    // NNCG: the sweep's step g = x_{k+1} - x_k plays -grad f; beta = ||g_{k+1}||^2/||g_k||^2.
    double beta = 0.0;
    if (cg) {
      double stepNorm = 0.0;
      if (split) {
        sums.resize(static_cast<std::size_t>(r.size() / kEntriesPerPiece + 1));
        stepNorm = sumPieces(forPieces(
            r.size(), kEntriesPerPiece, [&](std::size_t k, Eigen::Index b, Eigen::Index e) {
              sums[k] = (r.segment(b, e - b) - previous.segment(b, e - b)).squaredNorm();
            }));
      } else {
        stepNorm = (r - previous).squaredNorm();
      }
      if (previousStepNorm > 0) beta = stepNorm / previousStepNorm;
      if (!(beta <= 1.0)) beta = 0.0;  // restart: p = 0
      previousStepNorm = stepNorm;
    }
    auto accelerate = [&] {  // x += beta p, then p = x_new - x_old (= beta p + g); p = 0 on restart
      if (!cg) return;
      if (split) {
        if (beta > 0) {
          assign(r, r + beta * direction);
          if (body) assign(dv, dv + beta * directionDv);
        }
        if (beta == 0.0 && sweep > 1) {
          assign(direction, Eigen::VectorXd::Zero(r.size()));
          if (body) assign(directionDv, Eigen::VectorXd::Zero(dv.size()));
        } else {
          assign(direction, r - previous);
          if (body) assign(directionDv, dv - previousDv);
        }
        return;
      }
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
    if (body && split) {  // u = q + J dv, then the sum, in pieces of blocks
      u.resize(p.q.size());
      sums.resize(static_cast<std::size_t>(nb / kBlocksPerCheck + 1));
      const std::size_t pieces =
          forPieces(nb, kBlocksPerCheck, [&](std::size_t k, Eigen::Index first, Eigen::Index last) {
            for (auto b = static_cast<int>(first); b < last; ++b) {
              const int off = p.offset[b];
              for (int a = 0; a < p.sizes[b]; ++a) u[off + a] = p.q[off + a];
              body->addBlockVelocity(b, dv, u.data() + off);
            }
            sums[k] = residualSquares(p.blocks, static_cast<int>(first), static_cast<int>(last),
                                      p.offset[first], r, u);
          });
      e = std::sqrt(sumPieces(pieces)) / (1.0 + p.qNorm);
    } else if (body) {  // u = q + J dv: one pass, dv is current
      u = p.q;
      for (int b = 0; b < nb; ++b) body->addBlockVelocity(b, dv, u.data() + p.offset[b]);
      e = p.residualFromVelocity(r, u);
    } else {
      p.velocity(r, u);
      e = p.residualFromVelocity(r, u);
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
