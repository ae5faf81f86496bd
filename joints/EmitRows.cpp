#include <coulomb/joints/EmitRows.hpp>
#include <coulomb/joints/JointConstraint.hpp>
#include <coulomb/joints/JointLimitMotor.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::joints {

int emitJointRows(const JointDef& def, const JointBodies& bodies, const Stabilization& policy,
                  double h, std::vector<RowBlock>& out) {
  ConstraintEval eval = evaluateJoint(def, bodies.poseA, bodies.poseB);
  RowBlock block;
  block.kind = RowKind::Equality;
  block.bodyA = def.bodyA;
  block.bodyB = def.bodyB;
  block.jacobianA = std::move(eval.jacobianA);
  block.jacobianB = std::move(eval.jacobianB);
  block.bias = RowVector::Zero(eval.rows());
  if (policy.method == StabilizationMethod::Baumgarte) {
    const BaumgarteSettings& b = policy.baumgarte;
    for (int i = 0; i < eval.rows(); ++i) {
      const double c = eval.error[i];
      block.bias[i] = b.beta * std::copysign(std::max(std::abs(c) - b.slop, 0.0), c) / h;
    }
  }
  out.push_back(std::move(block));
  int appended = 1;
  if (const auto coordinate = jointCoordinate(def, bodies.poseA, bodies.poseB)) {
    const double rate =
        coordinate->jacobianA.dot(bodies.twistA) + coordinate->jacobianB.dot(bodies.twistB);
    appended += appendLimitMotorRows(def, *coordinate, rate, policy.baumgarte.beta, h, out);
  }
  return appended;
}

}  // namespace coulomb::joints
