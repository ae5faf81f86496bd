#include <coulomb/solvers/direct/EqualityLdltSolver.hpp>

#include <algorithm>
#include <vector>

namespace coulomb::solvers {

std::optional<std::string> EqualityLdltSolver::notApplicable(const ContactProblem& problem) const {
  for (const ConstraintBlock& b : problem.blocks)
    if (b.kind != BlockKind::Equality)
      return std::string("ldlt solves equality rows only (a ") + blockKindName(b.kind) +
             " block is present)";
  return std::nullopt;
}

namespace {

// True when the rows of W come in threes, rows 3g .. 3g+2 with the same columns, made of whole
// threes (a ball joint's three rows, emitted together); then W is a matrix of 3 x 3 blocks.
bool rowsInThrees(const BlockSparseMatrix& W) {
  const int n = W.blockCount();
  if (n == 0 || n % 3 != 0) return false;
  for (int b = 0; b < n; ++b) {
    if (W.blockSize(b) != 1) return false;
    const int first = W.rowBegin(b), count = W.rowEnd(b) - first;
    if (count % 3 != 0) return false;
    const int lead = W.rowBegin(b - b % 3);  // the group's first row
    if (W.rowEnd(b - b % 3) - lead != count) return false;
    for (int k = 0; k < count; ++k) {
      const int column = W.blockColumn(first + k);
      if (column != W.blockColumn(lead + k) || column % 3 != k % 3 ||
          (k % 3 != 0 && column != W.blockColumn(first + k - 1) + 1))
        return false;
    }
  }
  return true;
}

}  // namespace

bool EqualityLdltSolver::blocksFromEntries(const BlockSparseMatrix& W, int n) const {
  // Block (g, h) of W from rows 3g .. 3g+2, columns 3h .. 3h+2; the lower triangle's blocks are
  // the pattern, in row order.
  Workspace& w = workspace_;
  if (!rowsInThrees(W)) return false;
  const int groups = n / 3;
  w.pairs.clear();
  w.diagonal.resize(groups);
  w.coupling.clear();
  int diagonals = 0;
  for (int g = 0; g < groups; ++g)
    for (int k = W.rowBegin(3 * g); k < W.rowEnd(3 * g); k += 3) {
      const int h = W.blockColumn(k) / 3;
      if (h > g) continue;
      BlockLdltOf<3>::Block block;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
          block(a, c) = W.blockValues(W.rowBegin(3 * g + a) + (k - W.rowBegin(3 * g)) + c)[0];
      if (h == g) {
        w.diagonal[g] = block;
        ++diagonals;
      } else {
        w.pairs.emplace_back(g, h);
        w.coupling.push_back(block);
      }
    }
  return diagonals == groups;  // a W without some diagonal block: by entries
}

bool EqualityLdltSolver::blocksFromFactors(const BodySpaceDelassus& f) const {
  // Rows in threes on the same bodies (a ball joint's three rows): block (g, h) = sum over the
  // bodies g and h share of J_g,b M_b^-1 J_h,b^T, straight from the factors (W is not formed).
  Workspace& w = workspace_;
  const int n = f.size();
  if (n == 0 || n % 3 != 0) return false;
  const int groups = n / 3;
  for (int b = 0; b < f.blockCount(); ++b)
    if (f.blockSize(b) != 1) return false;
  for (int g = 0; g < groups; ++g)
    for (int a = 1; a < 3; ++a)
      for (int side = 0; side < 2; ++side)
        if (f.blockBody(3 * g + a, side) != f.blockBody(3 * g, side)) return false;
  // The pattern and the products depend on the groups' bodies only (a chain's never change).
  bool samePattern = w.groupBodies.size() == 2 * static_cast<std::size_t>(groups);
  for (int g = 0; samePattern && g < groups; ++g)
    for (int side = 0; side < 2; ++side)
      samePattern = samePattern && w.groupBodies[2 * g + side] == f.blockBody(3 * g, side);
  if (!samePattern) productsFromBodies(f, groups);
  w.diagonal.resize(groups);
  w.coupling.resize(w.pairs.size());
  for (auto& block : w.diagonal) block.setZero();
  for (auto& block : w.coupling) block.setZero();
  for (const Workspace::Product& product : w.products) {
    BlockLdltOf<3>::Block& value =
        product.target < groups ? w.diagonal[product.target] : w.coupling[product.target - groups];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        const double* row = f.jacobianRow(3 * product.g + a, product.sideG);
        const double* column = f.inverseMassColumn(3 * product.h + c, product.sideH);
        double sum = 0.0;
        for (int k = 0; k < 6; ++k) sum += row[k] * column[k];
        value(a, c) += sum;
      }
  }
  return true;
}

void EqualityLdltSolver::productsFromBodies(const BodySpaceDelassus& f, int groups) const {
  Workspace& w = workspace_;
  w.groupBodies.resize(2 * static_cast<std::size_t>(groups));
  for (int g = 0; g < groups; ++g)
    for (int side = 0; side < 2; ++side) w.groupBodies[2 * g + side] = f.blockBody(3 * g, side);
  // The groups on each body, ascending (a counting sort by body).
  std::vector<int>& start = w.bodyStart;
  start.assign(f.bodyCount() + 1, 0);
  for (int g = 0; g < groups; ++g)
    for (int side = 0; side < 2; ++side)
      if (const int body = f.blockBody(3 * g, side); body >= 0) ++start[body + 1];
  for (int b = 0; b < f.bodyCount(); ++b) start[b + 1] += start[b];
  w.bodyGroups.resize(start.back());
  w.next.assign(start.begin(), start.end() - 1);
  for (int g = 0; g < groups; ++g)
    for (int side = 0; side < 2; ++side)
      if (const int body = f.blockBody(3 * g, side); body >= 0) w.bodyGroups[w.next[body]++] = g;
  // Block (g, h) sums over the shared bodies, sides in order; target g for (g, g), groups + the
  // pair's index for (g, h), h < g (the lower triangle's blocks, in row order).
  w.pairs.clear();
  w.products.clear();
  const auto addProducts = [&](int g, int h, int target) {
    for (int sg = 0; sg < 2; ++sg)
      for (int sh = 0; sh < 2; ++sh) {
        const int body = f.blockBody(3 * g, sg);
        if (body >= 0 && body == f.blockBody(3 * h, sh))
          w.products.push_back({g, h, sg, sh, target});
      }
  };
  std::vector<int>& lower = w.lower;
  for (int g = 0; g < groups; ++g) {
    addProducts(g, g, g);
    lower.clear();
    for (int side = 0; side < 2; ++side)
      if (const int body = f.blockBody(3 * g, side); body >= 0)
        for (int k = start[body]; k < start[body + 1]; ++k)
          if (w.bodyGroups[k] < g) lower.push_back(w.bodyGroups[k]);
    std::sort(lower.begin(), lower.end());
    lower.erase(std::unique(lower.begin(), lower.end()), lower.end());
    for (const int h : lower) {
      addProducts(g, h, groups + static_cast<int>(w.pairs.size()));
      w.pairs.emplace_back(g, h);
    }
  }
}

void EqualityLdltSolver::solvePrepared(const PreparedProblem& p, const SolveContext& /*context*/,
                                       Eigen::VectorXd& r, SolverReport& report) const {
  const int n = p.size();
  Workspace& w = workspace_;
  report.iterations = 1;
  report.nativeResidualName = "common residual of the direct solve";
  const bool byBlocks = p.bodySpace ? blocksFromFactors(*p.bodySpace) : blocksFromEntries(p.W(), n);
  if (byBlocks && !w.blockLdlt.analyzed(n / 3, w.pairs)) w.blockLdlt.analyze(n / 3, w.pairs);
  const bool factorized =
      byBlocks ? w.blockLdlt.factorize(w.diagonal, w.coupling)
               : factorizeByEntries(p.bodySpace ? p.bodySpace->toBlockSparse() : p.W(), n);
  if (!factorized) {
    report.status = SolverStatus::NumericalFailure;
    report.note("LDL^T factorization failed (W singular: redundant rows?)");
    return;
  }
  w.rhs = -p.q;
  if (byBlocks)
    w.blockLdlt.solve(w.rhs, w.x);
  else
    w.ldlt.solve(w.rhs, w.x);
  if (!w.x.allFinite()) {
    report.status = SolverStatus::NumericalFailure;
    report.note("LDL^T solve not finite (W singular: redundant rows?)");
    return;
  }
  r = w.x;
  // Measured by ContactSolver::solve's common residual (ignoresStart): one product with W less.
  report.status = SolverStatus::Converged;
}

bool EqualityLdltSolver::factorizeByEntries(const BlockSparseMatrix& W, int n) const {
  // The lower triangle, straight from the block rows, in a fixed order: the pattern of the last
  // solve is recognised and its analysis (ordering, elimination tree) reused.
  Workspace& w = workspace_;
  w.rows.clear();
  w.cols.clear();
  w.values.clear();
  for (int b = 0; b < W.blockCount(); ++b) {
    const int rb = W.blockOffset(b), sb = W.blockSize(b);
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
      const int c = W.blockColumn(k), rc = W.blockOffset(c), sc = W.blockSize(c);
      const double* v = W.blockValues(k);
      for (int i = 0; i < sb; ++i)
        for (int j = 0; j < sc; ++j)
          if (rc + j <= rb + i) {
            w.rows.push_back(rb + i);
            w.cols.push_back(rc + j);
            w.values.push_back(v[sc * i + j]);
          }
    }
  }
  if (!w.ldlt.analyzed(n, w.rows, w.cols)) w.ldlt.analyze(n, w.rows, w.cols);
  return w.ldlt.factorize(w.values);
}

}  // namespace coulomb::solvers
