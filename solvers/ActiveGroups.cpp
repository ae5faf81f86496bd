#include <coulomb/solvers/ActiveGroups.hpp>

#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/Residual.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>

namespace coulomb::solvers {
namespace {

bool isotropicContactsOnly(const ContactProblem& problem) {
  return std::all_of(problem.blocks.begin(), problem.blocks.end(),
                     [](const ConstraintBlock& b) { return b.isContact() && !b.anisotropic; });
}

bool actsAtStart(const ContactProblem& problem, int b) {  // approaching or resting, or pushed
  const bool warm = problem.warmStart && problem.warmStart->size() == problem.q.size();
  return problem.q[3 * b] <= 0.0 || (warm && (*problem.warmStart)[3 * b] > 0.0);
}

// Joins, in `sets`, every two acting contacts that share a block row of W.
template <class Acting>
void uniteThroughW(const BlockSparseMatrix& W, const Acting& acting, UnionFind& sets) {
  for (int b = 0; b < W.blockCount(); ++b) {
    if (!acting(b)) continue;
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k)
      if (const int c = W.blockColumn(k); c != b && acting(c)) sets.unite(b, c);
  }
}

}  // namespace

bool splitsByActingContacts(const ContactProblem& problem, UnionFind& sets) {
  const int blocks = static_cast<int>(problem.blocks.size());
  if (blocks < 2 || problem.q.size() != 3 * blocks || !isotropicContactsOnly(problem)) return false;
  // Union-find over what links two contacts: their bodies (body-space W) or W's blocks.
  const BodySpaceDelassus* body = problem.W.bodySpaceOperator();
  const BlockSparseMatrix* W = problem.W.blockSparseMatrix();
  if (body == nullptr && W == nullptr) return false;
  const int nodes = body != nullptr ? body->bodyCount() : blocks;
  sets.reset(nodes);
  auto nodeOf = [&](int b) {  // a node of contact b: a dynamic body of it, or b itself
    if (body == nullptr) return b;
    const int b0 = body->blockBody(b, 0);
    return b0 >= 0 ? b0 : body->blockBody(b, 1);
  };
  if (body != nullptr) {
    for (int b = 0; b < blocks; ++b) {
      if (!actsAtStart(problem, b)) continue;
      const int b0 = body->blockBody(b, 0), b1 = body->blockBody(b, 1);
      if (b0 >= 0 && b1 >= 0) sets.unite(b0, b1);
    }
  } else {
    uniteThroughW(
        *W, [&](int b) { return actsAtStart(problem, b); }, sets);
  }
  int first = -1;
  for (int b = 0; b < blocks; ++b) {
    if (!actsAtStart(problem, b)) continue;
    const int root = sets.find(nodeOf(b));
    if (first < 0) first = root;
    if (root != first) return true;
  }
  return false;
}

ActiveGroups activeGroups(const BlockSparseMatrix& W, const std::vector<char>& acts) {
  ActiveGroups groups;
  const int blocks = W.blockCount();
  UnionFind sets;
  sets.reset(blocks);
  uniteThroughW(
      W, [&](int b) { return acts[b] != 0; }, sets);
  groups.groupOfBlock.assign(blocks, -1);
  groups.indexInGroup.assign(blocks, -1);
  std::vector<int> groupOfRoot(blocks, -1), sizes;
  for (int b = 0; b < blocks; ++b) {
    if (!acts[b]) continue;
    int& g = groupOfRoot[sets.find(b)];
    if (g < 0) {
      g = groups.count++;
      sizes.push_back(0);
    }
    groups.groupOfBlock[b] = g;
    groups.indexInGroup[b] = sizes[g]++;
  }
  groups.largest = sizes.empty() ? 0 : *std::max_element(sizes.begin(), sizes.end());
  groups.memberStart.assign(groups.count + 1, 0);
  for (int g = 0; g < groups.count; ++g)
    groups.memberStart[g + 1] = groups.memberStart[g] + sizes[g];
  groups.members.resize(groups.memberStart.back());
  for (int b = 0; b < blocks; ++b)  // ascending within each group
    if (const int g = groups.groupOfBlock[b]; g >= 0)
      groups.members[groups.memberStart[g] + groups.indexInGroup[b]] = b;
  return groups;
}

ContactProblem groupProblem(const ContactProblem& problem, const BlockSparseMatrix& W,
                            const ActiveGroups& groups, int group,
                            const Eigen::VectorXd* warmStart) {
  const int* members = groups.members.data() + groups.memberStart[group];
  const int n = groups.memberStart[group + 1] - groups.memberStart[group];
  Eigen::VectorXd q(3 * n);
  std::vector<double> mu(n);
  for (int i = 0; i < n; ++i) {
    q.segment<3>(3 * i) = problem.q.segment<3>(3 * members[i]);
    mu[i] = problem.blocks[members[i]].mu;
  }
  // A body-space island's group keeps W's factors on its own bodies: it is solved as an island
  // of those bodies would be (the Newton step in body space, the sticking start).
  DelassusOperator groupW;
  if (const BodySpaceDelassus* body = problem.W.bodySpaceOperator()) {
    auto factors = std::make_shared<BodySpaceDelassus>(0, std::vector<int>{});
    std::vector<int> localOf;
    body->extract(members, n, *factors, localOf);
    groupW = DelassusOperator::bodySpace(std::move(factors));
  } else {
    std::vector<int> rowStart{0}, columns;
    std::vector<double> values;
    for (int i = 0; i < n; ++i) {
      // W's block rows keep their columns in ascending order, and indexInGroup ascends with them.
      for (int k = W.rowBegin(members[i]); k < W.rowEnd(members[i]); ++k) {
        const int column = W.blockColumn(k);
        if (groups.groupOfBlock[column] != group) continue;
        columns.push_back(groups.indexInGroup[column]);
        values.insert(values.end(), W.blockValues(k), W.blockValues(k) + 9);
      }
      rowStart.push_back(static_cast<int>(columns.size()));
    }
    groupW = DelassusOperator::blockSparse(BlockSparseMatrix::fromBlockCsr(
        std::vector<int>(n, 3), std::move(rowStart), std::move(columns), std::move(values)));
  }
  ContactProblem sub = ContactProblem::contacts(std::move(groupW), std::move(q), mu,
                                                problem.name + "_group" + std::to_string(group));
  if (warmStart != nullptr) {
    Eigen::VectorXd warm(3 * n);
    for (int i = 0; i < n; ++i) warm.segment<3>(3 * i) = warmStart->segment<3>(3 * members[i]);
    sub.warmStart = std::move(warm);
  }
  return sub;
}

std::optional<PlanOutcome> solveByActiveGroups(const ContactProblem& problem,
                                               const SolverChooser& chooser,
                                               const SolverChoice& choice,
                                               const SolverOptions& options,
                                               const SolverRegistry& registry, bool* failedCheck,
                                               SolverInstances* instances) {
  if (failedCheck) *failedCheck = false;
  const int blocks = static_cast<int>(problem.blocks.size());
  if (blocks < 2 || problem.q.size() != 3 * blocks || !isotropicContactsOnly(problem))
    return std::nullopt;
  const auto started = std::chrono::steady_clock::now();
  std::optional<BlockSparseMatrix> converted;
  const BlockSparseMatrix* W = problem.W.blockSparseMatrix();
  if (W == nullptr) W = &converted.emplace(problem.W.toBlockSparse(problem.blockSizes()));
  // The island's lent workspaces are of its size, not a group's; a group is small enough for one
  // thread (the island's task runs it).
  SolverOptions groupOptions = options;
  groupOptions.stickingWorkspace = nullptr;
  groupOptions.arrivalRows = nullptr;
  groupOptions.parallel = nullptr;
  const Eigen::VectorXd* warm = problem.warmStart && problem.warmStart->size() == problem.q.size()
                                    ? &*problem.warmStart
                                    : nullptr;
  std::vector<char> acts(blocks);
  for (int b = 0; b < blocks; ++b) acts[b] = actsAtStart(problem, b);
  PlanOutcome out;
  Eigen::VectorXd &r = out.best.impulses, &u = out.best.velocities;
  r.setZero(problem.size());
  int iterations = 0, rounds = 0;
  ActiveGroups groups;
  for (bool approaching = true; approaching; ++rounds) {
    groups = activeGroups(*W, acts);
    if (groups.count < 2) return std::nullopt;  // they do not split (any more)
    out.attempts.clear();
    for (int g = 0; g < groups.count; ++g) {
      const ContactProblem sub = groupProblem(problem, *W, groups, g, rounds == 0 ? warm : &r);
      const SolvePlan plan = chooser.choose(sub, {}, choice, groupOptions);
      const PlanOutcome solved = instances ? solveWithFallback(sub, plan, registry, *instances)
                                           : solveWithFallback(sub, plan, registry);
      iterations += solved.iterations();
      for (int i = groups.memberStart[g]; i < groups.memberStart[g + 1]; ++i)
        r.segment<3>(3 * groups.members[i]) =
            solved.best.impulses.segment<3>(3 * (i - groups.memberStart[g]));
      out.attempts.insert(out.attempts.end(), solved.attempts.begin(), solved.attempts.end());
    }
    problem.W.velocity(r, problem.q, u);
    approaching = false;  // left-out contacts that the groups drive into approach act too
    for (int b = 0; b < blocks; ++b)
      if (!acts[b] && u[3 * b] < 0.0) acts[b] = approaching = true;
  }
  const ResidualValue e = commonResidual(problem, r, u);
  SolverReport& report = out.best.report;
  report.solver = "groups";
  report.iterations = iterations;
  report.residual = e.relative;
  report.absoluteResidual = e.absolute;
  report.status =
      e.relative <= options.tolerance ? SolverStatus::Converged : SolverStatus::MaxIterations;
  char msg[160];
  std::snprintf(msg, sizeof msg,
                "%d groups of acting contacts (largest %d of %d contacts) solved alone, %d rounds",
                groups.count, groups.largest, blocks, rounds);
  report.note(msg);
  report.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  out.seconds = report.seconds;
  out.status = report.status;
  if (!report.converged()) {
    if (failedCheck) *failedCheck = true;
    return std::nullopt;
  }
  out.attempts.insert(out.attempts.begin(), report);  // the whole answer, then the groups'
  return out;
}

}  // namespace coulomb::solvers
