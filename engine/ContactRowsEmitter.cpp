#include <coulomb/engine/ContactRowsEmitter.hpp>

#include <coulomb/joints/ContactRows.hpp>

#include <Eigen/Geometry>

#include <algorithm>

namespace coulomb::engine {
namespace {

Eigen::Vector3d pointVelocity(const geometry::BodyState& state, const geometry::BodyId& body,
                              const Eigen::Vector3d& point) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  const std::uint32_t i = body.index;
  return state.linearVelocities[i] +
         state.angularVelocities[i].cross(point - state.poses[i].position);
}

Eigen::Vector3d centreOf(const geometry::BodyState& state, const geometry::BodyId& body) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  return state.poses[body.index].position;
}

}  // namespace

joints::RowSet emitContactRows(const Island& island,
                               const std::vector<geometry::ContactManifold>& manifolds,
                               const geometry::BodyState& state, const ContactSettings& settings,
                               double h, std::vector<ContactRowSource>& sources) {
  joints::RowSet rows;
  sources.clear();
  for (const std::int32_t m : island.constraints) {
    const geometry::ContactManifold& manifold = manifolds[m];
    for (int p = 0; p < manifold.pointCount; ++p) {
      const geometry::ContactPoint& point = manifold.points[p];
      joints::ContactPointFrame frame;
      frame.bodyA = manifold.bodyA;
      frame.bodyB = manifold.bodyB;
      frame.point = point.position;
      frame.normal = manifold.normal;
      frame.tangent1 = manifold.tangent1;
      frame.tangent2 = manifold.tangent2;
      frame.centreA = centreOf(state, manifold.bodyA);
      frame.centreB = centreOf(state, manifold.bodyB);
      frame.friction = manifold.friction;
      frame.key = (static_cast<std::uint64_t>(manifold.colliderA.index) << 40) ^
                  (static_cast<std::uint64_t>(manifold.colliderB.index) << 16) ^ point.featureId;

      // Newton's restitution law on the normal velocity before the impulse (v*): the target is
      // u_N+ >= -e u_N-, i.e. the bias e u_N- (< 0) added to u_N (survey, sec. 5.4).
      const double approach =
          manifold.normal.dot(pointVelocity(state, manifold.bodyB, point.position) -
                              pointVelocity(state, manifold.bodyA, point.position));
      const bool impact = manifold.restitution > 0.0 && approach < -settings.restitutionThreshold;
      const double gap = -point.depth;
      double bias = impact ? manifold.restitution * approach : 0.0;
      // Speculative gap (wider than the touching tolerance, which is rounding: SCENES.md A7):
      // u_N >= -gap/h lets the bodies close the gap within the step and no more, and a point
      // that does not close gets no impulse. A point that v* closes within the step
      // (-approach h > gap) is an impact at the moment it closes: Newton's law as for a touching
      // point, u_N+ >= -e u_N- (survey, sec. 5.4), not stopped at the surface to bounce from
      // what is left of its speed in the next step (docs/tuning.md, "Impact laws").
      if (gap > settings.touchingTolerance && settings.speculativeContacts &&
          !(impact && -approach * h > gap))
        bias = gap / h;
      bias += baumgarteBias(settings.penetration, point.depth, h);
      frame.normalVelocityBias = bias;

      joints::RowBlock block = joints::makeContactRows(frame);
      if (point.warmStarted) {
        block.warmStart.resize(block.rows());
        block.warmStart[0] = point.normalImpulse;
        if (block.rows() == 3) block.warmStart.tail<2>() = point.tangentImpulse;
      }
      rows.blocks.push_back(std::move(block));
      sources.push_back({m, p, point.depth});
    }
  }
  return rows;
}

void storeContactImpulses(const joints::RowSet& rows, const std::vector<RowBlockSlot>& slots,
                          const Eigen::VectorXd& lambda,
                          const std::vector<ContactRowSource>& sources,
                          std::vector<geometry::ContactManifold>& manifolds) {
  for (std::size_t k = 0; k < rows.blocks.size(); ++k) {
    geometry::ContactPoint& point = manifolds[sources[k].manifold].points[sources[k].point];
    point.normalImpulse = lambda[slots[k].offset];
    point.tangentImpulse = rows.blocks[k].rows() == 3
                               ? Eigen::Vector2d(lambda.segment<2>(slots[k].offset + 1))
                               : Eigen::Vector2d::Zero();
  }
}

}  // namespace coulomb::engine
