#include <coulomb/joints/JointPrimitives.hpp>

namespace coulomb::joints {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

}  // namespace

WorldFrame toWorld(const JointFrame& frame, const geometry::Pose& comPose) {
  WorldFrame w;
  w.arm = comPose.rotation * frame.anchor;
  w.anchor = comPose.position + w.arm;
  w.axis = comPose.rotation * frame.axis;
  w.normal = comPose.rotation * frame.normal;
  w.binormal = w.axis.cross(w.normal);
  return w;
}

void setPointRows(ConstraintEval& out, int first, const WorldFrame& a, const WorldFrame& b) {
  out.error.segment<3>(first) = b.anchor - a.anchor;
  out.jacobianA.block<3, 3>(first, 0) = -Eigen::Matrix3d::Identity();
  out.jacobianA.block<3, 3>(first, 3) = skew(a.arm);
  out.jacobianB.block<3, 3>(first, 0) = Eigen::Matrix3d::Identity();
  out.jacobianB.block<3, 3>(first, 3) = -skew(b.arm);
}

void setDotRow(ConstraintEval& out, int row, const Eigen::Vector3d& uA, const Eigen::Vector3d& vB) {
  const Eigen::Vector3d c = uA.cross(vB);
  out.error[row] = uA.dot(vB);
  out.jacobianA.row(row) << 0.0, 0.0, 0.0, c.transpose();
  out.jacobianB.row(row) << 0.0, 0.0, 0.0, -c.transpose();
}

void setAlongRow(ConstraintEval& out, int row, const Eigen::Vector3d& tA, const WorldFrame& a,
                 const WorldFrame& b) {
  const Eigen::Vector3d d = b.anchor - a.anchor;
  out.error[row] = tA.dot(d);
  out.jacobianA.row(row) << -tA.transpose(), tA.cross(d + a.arm).transpose();
  out.jacobianB.row(row) << tA.transpose(), b.arm.cross(tA).transpose();
}

void setOrientationRows(ConstraintEval& out, int first, const WorldFrame& a, const WorldFrame& b) {
  setDotRow(out, first, a.axis, b.normal);
  setDotRow(out, first + 1, a.normal, b.binormal);
  setDotRow(out, first + 2, a.binormal, b.axis);
}

}  // namespace coulomb::joints
