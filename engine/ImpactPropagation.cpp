#include <coulomb/engine/ImpactPropagation.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace coulomb::engine {
namespace {

using geometry::BodyId;
using geometry::BodyState;
using geometry::ContactManifold;
using geometry::ContactPoint;

// [m/s] Approach speeds below this are round-off (an e = 0 impact leaves u_N ~ -1e-17), so a
// zero restitution threshold cannot make the sweeps chase rounding.
constexpr double kRoundOffSpeed = 1e-12;
// Gauss-Seidel sweeps of one pair problem (<= 4 points; one point is exact in one sweep).
constexpr int kPairSweeps = 64;
constexpr int kMaxPoints = ContactManifold::kMaxPoints;

bool isMovable(const BodyState& state, const BodyId& body) {
  return body.valid() && body.index < state.size() && state.isDynamic(body.index);
}

bool isKinematic(const BodyState& state, const BodyId& body) {
  return body.valid() && body.index < state.size() && state.alive[body.index] != 0 &&
         state.motionTypes[body.index] == geometry::MotionType::Kinematic;
}

Eigen::Vector3d pointVelocity(const BodyState& state, const BodyId& body,
                              const Eigen::Vector3d& point) {
  if (!body.valid() || body.index >= state.size()) return Eigen::Vector3d::Zero();
  const std::uint32_t i = body.index;
  return state.linearVelocities[i] +
         state.angularVelocities[i].cross(point - state.poses[i].position);
}

double normalVelocity(const BodyState& state, const ContactManifold& m, const ContactPoint& p) {
  return m.normal.dot(pointVelocity(state, m.bodyB, p.position) -
                      pointVelocity(state, m.bodyA, p.position));
}

// Touching, or a speculative gap that the normal velocity u_N closes within the step
// (-u_N h > gap): an impact at the moment it closes, as in the velocity problem
// (ContactRowsEmitter.cpp), so a striker found one step ahead by the swept margin
// (docs/collision.md) still impacts here with its whole speed.
bool inContact(const ContactPoint& p, double normalVelocity, const ContactSettings& settings,
               double h) {
  return p.depth >= -settings.touchingTolerance || -normalVelocity * h > -p.depth;
}

double impactSpeed(const ContactSettings& settings) {
  return std::max(settings.restitutionThreshold, kRoundOffSpeed);
}

bool impacts(const BodyState& state, const ContactManifold& m, const ContactSettings& settings,
             double h) {
  if (isKinematic(state, m.bodyA) || isKinematic(state, m.bodyB)) return false;
  if (!isMovable(state, m.bodyA) && !isMovable(state, m.bodyB)) return false;
  for (const ContactPoint& p : m.activePoints()) {
    const double u = normalVelocity(state, m, p);
    if (u < -impactSpeed(settings) && inContact(p, u, settings, h)) return true;
  }
  return false;
}

// One side of the pair: M^-1 J^T for the normal row of each point (J = +-(n, r x n)).
struct Side {
  bool movable = false;
  std::uint32_t index = 0;
  double inverseMass = 0.0;
  std::array<Eigen::Vector3d, kMaxPoints> arm{};          // r_k x n
  std::array<Eigen::Vector3d, kMaxPoints> angularGain{};  // I^-1 (r_k x n)
};

Side makeSide(const BodyState& state, const BodyId& body, const ContactManifold& m) {
  Side side;
  side.movable = isMovable(state, body);
  if (!side.movable) return side;
  side.index = body.index;
  side.inverseMass = state.inverseMasses[body.index];
  for (int k = 0; k < m.pointCount; ++k) {
    side.arm[k] = (m.points[k].position - state.poses[body.index].position).cross(m.normal);
    side.angularGain[k] = state.worldInverseInertias[body.index] * side.arm[k];
  }
  return side;
}

// The collision of the manifold's two bodies alone: Newton's law u_N+ >= -e u_N- on every
// touching point that approaches faster than the threshold (u_N+ >= 0 on the other touching
// points), impulses >= 0 and complementary (survey sec. 2.1.6), solved by projected Gauss-Seidel
// on the pair's <= 4 x 4 Delassus matrix W = J M^-1 J^T. Applies the impulses to the velocities.
void resolvePair(const ContactManifold& m, const ContactSettings& settings, double h,
                 BodyState& state) {
  const Side a = makeSide(state, m.bodyA, m), b = makeSide(state, m.bodyB, m);
  const int n = m.pointCount;
  Eigen::Matrix4d W = Eigen::Matrix4d::Zero();
  for (int k = 0; k < n; ++k)
    for (int l = 0; l < n; ++l) {
      if (a.movable) W(k, l) += a.inverseMass + a.arm[k].dot(a.angularGain[l]);
      if (b.movable) W(k, l) += b.inverseMass + b.arm[k].dot(b.angularGain[l]);
    }
  Eigen::Vector4d u = Eigen::Vector4d::Zero(), target = Eigen::Vector4d::Zero();
  Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
  std::array<bool, kMaxPoints> active{};
  for (int k = 0; k < n; ++k) {
    u[k] = normalVelocity(state, m, m.points[k]);
    active[k] = inContact(m.points[k], u[k], settings, h) && W(k, k) > 0.0;
    if (u[k] < -impactSpeed(settings))
      target[k] = -m.restitution * u[k];
    else if (m.points[k].depth < -settings.touchingTolerance)
      target[k] = m.points[k].depth / h;  // a slow speculative point may close its gap, no more
  }
  for (int sweep = 0; sweep < kPairSweeps; ++sweep) {
    double change = 0.0;
    for (int k = 0; k < n; ++k) {
      if (!active[k]) continue;
      const double next = std::max(0.0, lambda[k] - (u[k] - target[k]) / W(k, k));
      const double delta = next - lambda[k];
      lambda[k] = next;
      u += W.col(k) * delta;
      change = std::max(change, std::abs(delta));
    }
    if (change <= 1e-15 * lambda.cwiseAbs().maxCoeff()) break;
  }
  const double total = lambda.head(n).sum();
  for (const auto& [side, sign] : {std::pair{&a, -1.0}, std::pair{&b, 1.0}}) {
    if (!side->movable) continue;
    Eigen::Vector3d angular = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) angular += lambda[k] * side->angularGain[k];
    state.linearVelocities[side->index] += sign * side->inverseMass * total * m.normal;
    state.angularVelocities[side->index] += sign * angular;
  }
}

}  // namespace

ImpactPropagationReport propagateImpacts(std::span<const std::int32_t> contacts,
                                         const std::vector<ContactManifold>& manifolds,
                                         const ContactSettings& settings, double h,
                                         BodyState& state) {
  ImpactPropagationReport report;
  // Sweeps in the island's (deterministic) contact order; each impacting pair is resolved at
  // once, so an impact travels along a chain ordered like the contacts within one sweep.
  for (int sweep = 0; sweep < settings.maxImpactSweeps; ++sweep) {
    bool any = false;
    for (const std::int32_t edge : contacts) {
      const ContactManifold& m = manifolds[edge];
      if (!impacts(state, m, settings, h)) continue;
      resolvePair(m, settings, h, state);
      ++report.pairImpacts;
      any = true;
    }
    report.sweeps = sweep + 1;
    if (!any) return report;
  }
  report.converged = std::none_of(contacts.begin(), contacts.end(), [&](std::int32_t edge) {
    return impacts(state, manifolds[edge], settings, h);
  });
  return report;
}

}  // namespace coulomb::engine
