#include <coulomb/joints/JointLimitMotor.hpp>

#include <algorithm>

namespace coulomb::joints {
namespace {

RowBlock coordinateBlock(const JointDef& def, RowKind kind, int rows) {
  RowBlock block;
  block.kind = kind;
  block.bodyA = def.bodyA;
  block.bodyB = def.bodyB;
  block.jacobianA = RowJacobian::Zero(rows, 6);
  block.jacobianB = RowJacobian::Zero(rows, 6);
  block.bias = RowVector::Zero(rows);
  return block;
}

/// Bias of one stop with gap g (>= 0 inside) approached at `rate` (d g/dt).
double stopBias(double gap, double rate, double restitution, double beta, double h) {
  if (gap < 0.0) return beta * gap / h;  // crossed: push back out (Baumgarte)
  const bool reachedThisStep = gap + h * rate <= 0.0;
  if (restitution > 0.0 && reachedThisStep && rate < -kLimitBounceThreshold)
    return restitution * rate;  // u+ >= -e u-: bounce (survey sec. 5.4)
  return gap / h;               // speculative: may close the gap, not cross it
}

}  // namespace

int appendLimitMotorRows(const JointDef& def, const JointCoordinate& coordinate,
                         double coordinateRate, double beta, double h, std::vector<RowBlock>& out) {
  int appended = 0;
  if (def.limit.enabled) {
    struct Stop {
      double sign;  // +1: lower stop, gap = c - lower; -1: upper stop, gap = upper - c
      double gap;
    };
    std::vector<Stop> stops;
    for (const Stop s : {Stop{1.0, coordinate.value - def.limit.lower},
                         Stop{-1.0, def.limit.upper - coordinate.value}}) {
      const double rate = s.sign * coordinateRate;
      // Within reach: already crossed, touching, or closing it within two steps at this rate.
      if (s.gap + 2.0 * h * std::min(rate, 0.0) <= 1e-12) stops.push_back(s);
    }
    if (!stops.empty()) {
      RowBlock block = coordinateBlock(def, RowKind::Unilateral, static_cast<int>(stops.size()));
      for (std::size_t i = 0; i < stops.size(); ++i) {
        block.jacobianA.row(i) = stops[i].sign * coordinate.jacobianA;
        block.jacobianB.row(i) = stops[i].sign * coordinate.jacobianB;
        block.bias[i] =
            stopBias(stops[i].gap, stops[i].sign * coordinateRate, def.limit.restitution, beta, h);
      }
      out.push_back(std::move(block));
      ++appended;
    }
  }
  const bool motor = def.motor.enabled;
  if (motor || def.friction > 0.0) {
    RowBlock block = coordinateBlock(def, RowKind::Bounded, 1);
    block.jacobianA.row(0) = coordinate.jacobianA;
    block.jacobianB.row(0) = coordinate.jacobianB;
    block.bias[0] = motor ? -def.motor.targetVelocity : 0.0;
    const double bound = (motor ? def.motor.maxForce : def.friction) * h;
    block.lower = RowVector::Constant(1, -bound);
    block.upper = RowVector::Constant(1, bound);
    out.push_back(std::move(block));
    ++appended;
  }
  return appended;
}

}  // namespace coulomb::joints
