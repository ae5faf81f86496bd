#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <vector>

namespace coulomb::solvers {

double inverseSpectralRadius(const Eigen::Matrix3d& block) {
  const Eigen::Matrix3d s = 0.5 * (block + block.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(s, Eigen::EigenvaluesOnly);
  const double lmax = eig.eigenvalues().maxCoeff();
  return lmax > 0 ? 1.0 / lmax : 0.0;
}

double inverseTangentSpectralRadius(const Eigen::Matrix3d& block) {
  // lambda_max of the symmetric 2x2 part: (s11 + s22)/2 + sqrt(((s11 - s22)/2)^2 + s12^2).
  const double s11 = block(1, 1), s22 = block(2, 2), s12 = 0.5 * (block(1, 2) + block(2, 1));
  const double lmax = 0.5 * (s11 + s22) + std::hypot(0.5 * (s11 - s22), s12);
  return lmax > 0 ? 1.0 / lmax : 0.0;
}

void PgsSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                              Eigen::VectorXd& r, SolverReport& report) const {
  const PgsOptions::Update mode = options_.update;
  std::vector<Local>& local = local_;
  local.resize(p.blockCount());
  for (int b = 0; b < p.blockCount(); ++b) {
    if (!p.blocks[b].isContact()) continue;
    Local& l = local[b];
    l.W = p.contactBlock(b);
    if (mode == PgsOptions::Update::ConeProjection) {
      l.rho = inverseSpectralRadius(l.W);
    } else {  // (3.2): only the normal and tangential steps
      l.rhoN = 1.0 / l.W(0, 0);
      l.rhoT = inverseTangentSpectralRadius(l.W);
    }
  }
  auto rule = [&](int b, const Eigen::Vector3d& qt, Eigen::Vector3d& rc) {
    const Local& l = local[b];
    const double mu = p.blocks[b].mu;
    Eigen::Vector3d u = l.W * rc + qt;
    if (mode == PgsOptions::Update::ConeProjection) {  // (3.3)
      double x[3] = {rc[0] - l.rho * (u[0] + mu * tangentNorm(u[1], u[2])), rc[1] - l.rho * u[1],
                     rc[2] - l.rho * u[2]};
      projectOntoCone(x, mu);
      rc = Eigen::Vector3d(x[0], x[1], x[2]);
      return;
    }
    const double rN = std::max(rc[0] - l.rhoN * u[0], 0.0);  // (3.2) normal
    u += l.W.col(0) * (rN - rc[0]);
    rc[0] = rN;
    const Eigen::Vector2d rT =
        projectOntoDisk(Eigen::Vector2d(rc[1] - l.rhoT * u[1], rc[2] - l.rhoT * u[2]), mu * rN);
    rc[1] = rT[0];
    rc[2] = rT[1];
  };
  GaussSeidelSettings gs;
  gs.omega = options_.omega;
  gs.conjugateGradient = options_.conjugateGradient;
  gs.shuffle = options_.shuffle;
  gs.seed = options_.seed;
  gs.stallWindow = options_.stallWindow;
  gs.residualInterval = options_.residualInterval;
  runGaussSeidel(p, context, gs, ContactUpdate(rule), r, report, &workspace_);
}

}  // namespace coulomb::solvers
