#include <coulomb/solvers/PreparedProblem.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/Residual.hpp>

#include <algorithm>
#include <cstring>

namespace coulomb::solvers {

PreparedProblem PreparedProblem::from(const ContactProblem& problem, bool keepBodySpace) {
  PreparedProblem p;
  p.assign(problem, keepBodySpace);
  return p;
}

void PreparedProblem::assign(const ContactProblem& problem, bool keepBodySpace) {
  PreparedProblem& p = *this;
  p.start.known = p.end.known = false;  // their vectors keep their storage
  p.bodySpace.reset();
  p.factors.reset();
  p.sharedW.reset();
  p.factorsShift = 0.0;
  p.diagonalBlocks = nullptr;
  p.scale.resize(0);
  p.maxDiagonal = 0.0;
  p.blocks.assign(problem.blocks.begin(), problem.blocks.end());
  p.offset.assign(problem.blocks.size() + 1, 0);
  p.sizes.resize(problem.blocks.size());
  for (std::size_t b = 0; b < problem.blocks.size(); ++b) {
    p.sizes[b] = problem.blocks[b].size();
    p.offset[b + 1] = p.offset[b] + p.sizes[b];
  }
  p.q = problem.q;
  // Sized with the problem: a steady step allocates nothing when one is first recorded.
  p.start.u.resize(p.q.size());
  p.end.r.resize(p.q.size());
  p.end.u.resize(p.q.size());
  bool anisotropic = false;
  for (const ConstraintBlock& b : p.blocks) anisotropic |= b.isContact() && b.anisotropic;
  if (!anisotropic && problem.W.bodySpaceOperator()) p.factors = problem.W.sharedBodySpace();
  if (keepBodySpace && !anisotropic && problem.W.bodySpaceOperator()) {
    p.bodySpace = problem.W.sharedBodySpace();
    p.diagonalBlocks = p.bodySpace->diagonalBlocks().data();
  } else if (const BlockSparseMatrix* own = problem.W.blockSparseMatrix();
             !anisotropic && own != nullptr && own->blockSizes() == p.sizes) {
    p.sharedW = problem.W.sharedBlockSparse();  // read in place: no copy of W per solve
  } else {
    problem.W.toBlockSparse(p.sizes, p.ownW);
  }
  if (anisotropic) {
    p.scale = Eigen::VectorXd::Ones(p.size());
    for (size_t b = 0; b < p.blocks.size(); ++b) {
      ConstraintBlock& k = p.blocks[b];
      if (!k.isContact() || !k.anisotropic) continue;
      p.scale[p.offset[b] + 1] = k.mu1;
      p.scale[p.offset[b] + 2] = k.mu2;
      k = ConstraintBlock::contact(1.0);
    }
    p.ownW = p.W().scaledSymmetric(p.scale);
    p.sharedW.reset();
    p.q = p.q.cwiseProduct(p.scale);
  }
  p.qNorm = plainNorm(p.q);
  p.maxDiagonal = largestDiagonal();
}

BlockSparseMatrix& PreparedProblem::writableW() {
  if (sharedW) {
    ownW = *sharedW;
    sharedW.reset();
  }
  return ownW;
}

double PreparedProblem::largestDiagonal() const {
  double largest = 0.0;
  for (int b = 0; b < blockCount(); ++b) {  // max_i W_ii, block by block (no row search)
    const double* d = diagonalBlock(b);
    const int s = blocks[b].size();
    for (int a = 0; a < s; ++a) largest = std::max(largest, d[(s + 1) * a]);
  }
  return largest;
}

void PreparedProblem::formExplicitW(const ContactProblem& problem) {
  if (!bodySpace) return;
  problem.W.toBlockSparse(sizes, ownW);
  sharedW.reset();
  bodySpace.reset();
  diagonalBlocks = nullptr;
  maxDiagonal = largestDiagonal();
}

const double* PreparedProblem::diagonalBlock(int b) const {
  return bodySpace ? diagonalBlocks + 9 * static_cast<std::ptrdiff_t>(b)
                   : W().blockValues(W().diagonalBlock(b));
}

Eigen::Matrix3d PreparedProblem::contactBlock(int b) const {
  const double* v = diagonalBlock(b);
  Eigen::Matrix3d m;
  m << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  return m;
}

double PreparedProblem::diagonal(int row) const {
  const int b =
      static_cast<int>(std::upper_bound(offset.begin(), offset.end(), row) - offset.begin()) - 1;
  const int a = row - offset[b], s = blocks[b].size();
  return diagonalBlock(b)[(s + 1) * a];
}

void PreparedProblem::velocity(const Eigen::VectorXd& r, Eigen::VectorXd& u) const {
  u = q;
  // r = 0 (every solve's first candidate): W r = 0 exactly (the factors are finite), u = q.
  if (std::all_of(r.data(), r.data() + r.size(), [](double x) { return x == 0.0; })) return;
  if (bodySpace)
    bodySpace->multiplyAdd(r, u);
  else
    W().multiplyAdd(r, u);
}

double PreparedProblem::residualFromVelocity(const Eigen::VectorXd& r, const Eigen::VectorXd& u,
                                             double* absolute) const {
  const double value = solvers::residualFromVelocity(blocks, r, u);
  if (absolute != nullptr) *absolute = value;
  return value / (1.0 + qNorm);
}

double PreparedProblem::residual(const Eigen::VectorXd& r, Eigen::VectorXd& u,
                                 double* absolute) const {
  velocity(r, u);
  return residualFromVelocity(r, u, absolute);
}

double PreparedProblem::residual(const Eigen::VectorXd& r, Eigen::VectorXd& u, Eigen::VectorXd& dv,
                                 double* absolute) const {
  if (!bodySpace) return residual(r, u, absolute);
  u = q;
  if (std::all_of(r.data(), r.data() + r.size(), [](double x) { return x == 0.0; })) {
    // W r = 0: u = q (as velocity()); dv = +0 everywhere, what bodyVelocities gives for r = 0.
    dv.setZero(6 * bodySpace->bodyCount());
  } else {  // multiplyAdd's two passes, dv kept
    bodySpace->bodyVelocities(r, dv);
    bodySpace->addRowVelocities(dv, u.data());  // the same partition as `offset`
  }
  return residualFromVelocity(r, u, absolute);
}

bool PreparedProblem::startEvaluatedAs(const Eigen::VectorXd& r) const {
  return startIs(r) && start.u.size() == r.size() && start.inBodySpace == (bodySpace != nullptr);
}

void PreparedProblem::recordEnd(const Eigen::VectorXd& r, const Eigen::VectorXd& u, double residual,
                                double absolute) const {
  end.known = true;
  end.r = r;
  end.u = u;
  end.residual = residual;
  end.absolute = absolute;
  end.inBodySpace = bodySpace != nullptr;
}

bool PreparedProblem::KnownEvaluation::isOf(const Eigen::VectorXd& x) const {
  return known && x.size() == r.size() &&
         std::memcmp(x.data(), r.data(), sizeof(double) * static_cast<size_t>(x.size())) == 0;
}

bool PreparedProblem::startIs(const Eigen::VectorXd& r) const {
  return start.isOf(r);
}

void PreparedProblem::project(Eigen::VectorXd& r) const {
  for (int b = 0; b < blockCount(); ++b) {
    double* x = r.data() + offset[b];
    switch (blocks[b].kind) {
      case BlockKind::Contact3D:
        projectOntoCone(x, blocks[b].mu);
        break;
      case BlockKind::Unilateral:
        x[0] = std::max(x[0], 0.0);
        break;
      case BlockKind::Bounded:
        x[0] = std::clamp(x[0], blocks[b].lower, blocks[b].upper);
        break;
      case BlockKind::Equality:
        break;
    }
  }
}

Eigen::VectorXd PreparedProblem::toOriginal(const Eigen::VectorXd& r) const {
  Eigen::VectorXd out;
  toOriginal(r, out);
  return out;
}

Eigen::VectorXd PreparedProblem::fromOriginal(const Eigen::VectorXd& r) const {
  Eigen::VectorXd out;
  fromOriginal(r, out);
  return out;
}

void PreparedProblem::toOriginal(const Eigen::VectorXd& r, Eigen::VectorXd& out) const {
  if (scale.size() == 0)
    out = r;
  else
    out = r.cwiseProduct(scale);
}

void PreparedProblem::fromOriginal(const Eigen::VectorXd& r, Eigen::VectorXd& out) const {
  out = r;
  if (scale.size() == 0) return;
  for (int i = 0; i < size(); ++i) out[i] = scale[i] > 0 ? r[i] / scale[i] : 0.0;
}

SolveContext::SolveContext(const SolverOptions& options, Clock::time_point start)
    : options_(options), start_(start) {}

double SolveContext::elapsed() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

bool SolveContext::timeUp(SolverReport& report) const {
  if (elapsed() < options_.timeLimitSeconds) return false;
  report.timeLimitReached = true;
  return true;
}

void SolveContext::record(SolverReport& report, int iteration, double residual) const {
  if (options_.recordHistory) report.history.push_back({iteration, elapsed(), residual});
}

SolveContext SolveContext::withOptions(const SolverOptions& options) const {
  return SolveContext(options, start_);
}

}  // namespace coulomb::solvers
