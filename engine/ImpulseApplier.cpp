#include <coulomb/engine/ImpulseApplier.hpp>

namespace coulomb::engine {

namespace {

// J^T lambda of one side, row by row (J row-major, 6 per row): p += J_lin^T lambda, l += J_ang^T
// lambda. A plain loop, not Eigen's dynamic-size matrix-vector kernel.
inline void addRows(const double* j, const double* impulse, int rows, Eigen::Vector3d& p,
                    Eigen::Vector3d& l) {
  for (int i = 0; i < rows; ++i)
    for (int c = 0; c < 3; ++c) {
      p[c] += j[6 * i + c] * impulse[i];
      l[c] += j[6 * i + 3 + c] * impulse[i];
    }
}

void apply(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
           const Eigen::VectorXd& lambda, const geometry::BodyState& state,
           const InverseInertias& inverseInertias, std::vector<Eigen::Vector3d>& linear,
           std::vector<Eigen::Vector3d>& angular) {
  for (std::size_t k = 0; k < rows.blocks.size(); ++k) {
    const joints::RowBlock& block = rows.blocks[k];
    const double* impulse = lambda.data() + slots[k].offset;
    const int rows = slots[k].rows;
    for (const bool sideB : {false, true}) {
      const geometry::BodyId& body = sideB ? block.bodyB : block.bodyA;
      if (!body.valid() || body.index >= state.size() || !state.isDynamic(body.index)) continue;
      const joints::RowJacobian& jac = sideB ? block.jacobianB : block.jacobianA;
      // Generalised impulse J^T lambda = (linear impulse, angular impulse about the COM).
      Eigen::Vector3d p = Eigen::Vector3d::Zero(), l = Eigen::Vector3d::Zero();
      if (rows == 3)  // contacts and ball joints: the same sums with a constant trip count
        addRows(jac.data(), impulse, 3, p, l);
      else
        addRows(jac.data(), impulse, rows, p, l);
      linear[body.index] += state.inverseMasses[body.index] * p;
      angular[body.index] += inverseInertias[body.index] * l;
    }
  }
}

}  // namespace

void applyImpulsesTo(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
                     const Eigen::VectorXd& lambda, const geometry::BodyState& state,
                     std::vector<Eigen::Vector3d>& linear, std::vector<Eigen::Vector3d>& angular) {
  apply(rows, slots, lambda, state, state.worldInverseInertias, linear, angular);
}

void applyImpulses(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
                   const Eigen::VectorXd& lambda, geometry::BodyState& state,
                   const InverseInertias* inverseInertias) {
  apply(rows, slots, lambda, state,
        inverseInertias != nullptr ? *inverseInertias : state.worldInverseInertias,
        state.linearVelocities, state.angularVelocities);
}

}  // namespace coulomb::engine
