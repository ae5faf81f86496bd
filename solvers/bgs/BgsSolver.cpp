#include <coulomb/solvers/bgs/BgsSolver.hpp>

#include <coulomb/solvers/GaussSeidelLoop.hpp>

#include <vector>

namespace coulomb::solvers {

void BgsSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                              Eigen::VectorXd& r, SolverReport& report) const {
  std::vector<LocalContactData>& local = local_;
  local.resize(p.blockCount());
  for (int b = 0; b < p.blockCount(); ++b)
    if (p.blocks[b].isContact()) local[b] = LocalContactData::from(p.contactBlock(b));
  const LocalSolverSettings settings = options_.local;
  auto rule = [&](int b, const Eigen::Vector3d& qt, Eigen::Vector3d& rc) {
    rc = solveLocalContact(local[b], qt, p.blocks[b].mu, rc, settings).r;
  };
  GaussSeidelSettings gs;
  gs.omega = options_.omega;
  gs.conjugateGradient = options_.conjugateGradient;
  gs.omegaAfterStall = options_.omegaAfterStall;
  gs.stallWindow = options_.stallWindow;
  gs.shuffle = options_.shuffle;
  gs.seed = options_.seed;
  gs.residualInterval = options_.residualInterval;
  runGaussSeidel(p, context, gs, ContactUpdate(rule), r, report, &workspace_);
}

}  // namespace coulomb::solvers
