#include <coulomb/engine/ContactSource.hpp>

#include <coulomb/joints/ContactRows.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace coulomb::engine {
namespace {

Eigen::Vector3d pointVelocity(const geometry::BodyState& state, const geometry::BodyId& body,
                              const Eigen::Vector3d& point) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  const std::uint32_t i = body.index;
  return state.linearVelocities[i] +
         state.angularVelocities[i].cross(point - state.poses[i].position);
}

Eigen::Vector3d linearOf(const geometry::BodyState& state, const geometry::BodyId& body) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  return state.linearVelocities[body.index];
}

Eigen::Vector3d angularOf(const geometry::BodyState& state, const geometry::BodyId& body) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  return state.angularVelocities[body.index];
}

// Elastic turning (ContactSettings::elasticTurning, docs/tuning.md): the approach velocity of a
// persistent point (one of the last solve) that the turning of its normal since then causes,
// u_turn < 0, or 0. `approach` is n . v_rel at the point with the velocities v* of this step.
//
// Let v_k be the velocities at the start of the step (v* = v_k + h a, a = gravity and applied
// forces). The approach at v_k, n . v_rel(p, v_k), is the last solve's normal velocity u_old
// (stored with the point: exact where the solve pushed, u_N+ = -bias; the approach before the
// solve where it did not, exact unless the island's other impulses changed it) plus what the new
// geometry changes: n . v_rel(p, v) - n_old .
// v_rel(p_old, v), the same for v_k and v* up to (n - n_old) . h a, so gravity cancels. A
// separating u_old > 0 (left by the last reflection) belongs to the approach; a negative one (a
// speculative gap being closed) is not turning and stays inelastic:
//   u_turn = min(0, [n . v_rel(p, v*) - n_old . v_rel(p_old, v*)] + max(0, u_old)).
// For a sphere the moments r x n vanish, so a ball rolling without slip on a concave rail gets
// u_turn = (n - n_old) . v_centre + max(0, u_old): the reflection of the chord of an inscribed
// polygon. (Evaluating both normals at the new point instead would give ~0 for a rolling ball,
// whose contact point velocity is ~0; evaluating n_old . v_k without the max would add the last
// reflection to the next one and grow without bound.)
double turningApproach(const geometry::ContactManifold& manifold,
                       const geometry::ContactPoint& point, const geometry::BodyState& state,
                       double approach) {
  if (point.solvedNormal.squaredNorm() < 0.25) return 0.0;
  if (manifold.normal.dot(point.solvedNormal) < std::cos(kElasticTurningMaxAngle)) return 0.0;
  const Eigen::Vector3d& n0 = point.solvedNormal;
  const double old = n0.dot(linearOf(state, manifold.bodyB) - linearOf(state, manifold.bodyA)) +
                     angularOf(state, manifold.bodyB).dot(point.solvedMomentB) -
                     angularOf(state, manifold.bodyA).dot(point.solvedMomentA);
  return std::min(0.0, approach - old + std::max(0.0, point.solvedNormalVelocity));
}

Eigen::Vector3d centreOf(const geometry::BodyState& state, const geometry::BodyId& body) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  return state.poses[body.index].position;
}

}  // namespace

void ContactSource::appendEdges(std::uint8_t owner, const RowContext& context, StepEdges& edges) {
  const std::vector<geometry::ContactManifold>& manifolds = context.manifolds;
  for (std::size_t m = 0; m < manifolds.size(); ++m)
    if (!manifolds[m].sensor && manifolds[m].enabled)  // sensors and contacts turned off: no rows
      edges.add(owner, static_cast<std::int32_t>(m),
                {static_cast<std::int32_t>(manifolds[m].bodyA.index),
                 static_cast<std::int32_t>(manifolds[m].bodyB.index)});
}

void ContactSource::emitRows(std::span<const std::int32_t> items, const RowContext& context,
                             joints::RowSet& rows) {
  std::vector<geometry::ContactManifold>& manifolds = context.manifolds;
  const geometry::BodyState& state = context.state;
  const ContactSettings& settings = context.contact;
  const double h = context.h;
  std::size_t points = rows.blocks.size();  // one reservation: a RowBlock is ~0.8 KB
  for (const std::int32_t m : items) points += manifolds[m].pointCount;
  rows.blocks.reserve(points);
  for (const std::int32_t m : items) {
    geometry::ContactManifold& manifold = manifolds[m];
    for (int p = 0; p < manifold.pointCount; ++p) {
      geometry::ContactPoint& point = manifold.points[p];
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
      // A moving surface (ContactManifold::surfaceVelocity): friction sticks at
      // t . (v_B - v_A) = -t . s, so u_T carries +t . s.
      frame.tangentVelocityBias = {manifold.tangent1.dot(manifold.surfaceVelocity),
                                   manifold.tangent2.dot(manifold.surfaceVelocity)};
      frame.key = contactKey(m, p);

      // Newton's restitution law on the normal velocity before the impulse (v*): the target is
      // u_N+ >= -e u_N-, i.e. the bias e u_N- (< 0) added to u_N (survey, sec. 5.4).
      const double approach =
          manifold.normal.dot(pointVelocity(state, manifold.bodyB, point.position) -
                              pointVelocity(state, manifold.bodyA, point.position));
      const bool impact = manifold.restitution > 0.0 && approach < -settings.restitutionThreshold;
      const double gap = -point.depth;
      double bias = impact ? manifold.restitution * approach : 0.0;
      // Speculative gap (wider than the touching tolerance, which is rounding:
      // docs/scene-specifications.md A7): u_N >= -gap/h lets the bodies close the gap within the
      // step and no more, and a point that does not close gets no impulse. A point that v* closes
      // within the step
      // (-approach h > gap) is an impact at the moment it closes: Newton's law as for a touching
      // point, u_N+ >= -e u_N- (survey, sec. 5.4), not stopped at the surface to bounce from
      // what is left of its speed in the next step (docs/tuning.md, "Impact laws").
      if (gap > settings.touchingTolerance && settings.speculativeContacts &&
          !(impact && -approach * h > gap))
        bias = gap / h;
      // Elastic turning: u_N+ >= -u_turn, the part of the approach that the turning of a
      // persistent contact's normal causes, reflected (it overrides a speculative gap's
      // allowance: the chords of a concave surface end inside it by ~R theta^2 / 8).
      // Only a point in contact moves along the surface: one that touches now, or one that
      // pushed in the last solve and that v* closes within this step. A speculative point that
      // did not push is an approaching body whose impact follows Newton's law, even if the last
      // step already saw it (a plank spinning at 3 rad per step toward a box, a box falling
      // onto another that the impact tips: docs/tuning.md, "Elastic turning").
      const bool inContact =
          gap <= settings.touchingTolerance || (point.normalImpulse > 0.0 && -approach * h > gap);
      if (settings.elasticTurning && inContact) {
        const double turn = turningApproach(manifold, point, state, approach);
        if (turn < 0.0) bias = std::min(bias, turn);
      }
      bias += baumgarteBias(settings.penetration, point.depth, h);
      frame.normalVelocityBias = bias;

      joints::RowBlock block = joints::makeContactRows(frame);
      if (point.warmStarted) {
        block.warmStart.resize(block.rows());
        block.warmStart[0] = point.normalImpulse;
        if (block.rows() == 3) block.warmStart.tail<2>() = point.tangentImpulse;
      }
      // Kept with the point: the penetration stage reads the depth, storeImpulses the approach.
      point.approachVelocity = approach;
      rows.blocks.push_back(std::move(block));
    }
  }
}

void ContactSource::storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                                  const std::vector<RowBlockSlot>& slots,
                                  const Eigen::VectorXd& lambda, const RowContext& context) {
  std::vector<geometry::ContactManifold>& manifolds = context.manifolds;
  for (std::size_t k = range.first; k < range.end(); ++k) {
    const joints::RowBlock& block = rows.blocks[k];
    geometry::ContactPoint& point =
        manifolds[contactManifold(block.sourceKey)].points[contactPoint(block.sourceKey)];
    point.normalImpulse = lambda[slots[k].offset];
    // The normal row just solved, for the next step's elastic turning (turningApproach): its
    // Jacobian holds (-n, -r_A x n) and (n, r_B x n), and a loaded point (impulse > 0) leaves
    // the solve with u_N + bias = 0 (complementarity), so u_N+ = -bias.
    point.solvedNormal = block.jacobianB.row(0).head<3>().transpose();
    point.solvedMomentA = -block.jacobianA.row(0).tail<3>().transpose();
    point.solvedMomentB = block.jacobianB.row(0).tail<3>().transpose();
    point.solvedNormalVelocity =
        point.normalImpulse > 0.0 ? -block.bias[0] : point.approachVelocity;
    point.tangentImpulse = block.rows() == 3
                               ? Eigen::Vector2d(lambda.segment<2>(slots[k].offset + 1))
                               : Eigen::Vector2d::Zero();
  }
}

}  // namespace coulomb::engine
