#include <coulomb/engine/BodyBuilder.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/geometry/MassProperties.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::engine {
namespace {

using geometry::MotionType;

class Failure {
 public:
  explicit Failure(const BodyDesc& desc) {
    prefix_ = desc.name.empty() ? std::string("body") : "body '" + desc.name + "'";
  }
  [[noreturn]] void operator()(const std::string& message) const {
    throw CoulombError(prefix_ + ": " + message);
  }

 private:
  std::string prefix_;
};

std::string vectorText(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

void checkVector(const Failure& fail, const char* what, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(v[k]))
      fail(std::string(what) + "[" + std::to_string(k) + "] is not finite (got " + vectorText(v) +
           ")");
}

void checkPose(const Failure& fail, const std::string& what, const geometry::Pose& pose,
               double tolerance) {
  const std::string prefix = what.empty() ? what : what + ".";
  checkVector(fail, (prefix + "position").c_str(), pose.position);
  if (!pose.rotation.coeffs().allFinite()) fail(prefix + "orientation is not finite");
  const double norm = pose.rotation.norm();
  if (std::abs(norm - 1.0) > tolerance) {
    std::ostringstream out;
    out << prefix << "orientation must be a unit quaternion (norm " << norm << ")";
    fail(out.str());
  }
}

void checkMaterial(const Failure& fail, const std::string& what, const geometry::Material& m) {
  if (!std::isfinite(m.friction) || m.friction < 0.0)
    fail(what + ".friction must be finite and >= 0 (got " + std::to_string(m.friction) + ")");
  if (!std::isfinite(m.restitution) || m.restitution < 0.0 || m.restitution > 1.0)
    fail(what + ".restitution must be in [0, 1] (got " + std::to_string(m.restitution) + ")");
}

geometry::Pose normalised(geometry::Pose pose) {
  pose.rotation.normalize();
  return pose;
}

}  // namespace

ResolvedBody resolveBody(const BodyDesc& desc, const WorldSettings& settings) {
  const Failure fail(desc);
  checkPose(fail, "", desc.pose, settings.unitQuaternionTolerance);
  checkVector(fail, "linear_velocity", desc.linearVelocity);
  checkVector(fail, "angular_velocity", desc.angularVelocity);
  const bool dynamic = desc.motionType == MotionType::Dynamic;
  const double density = desc.density.value_or(settings.defaultDensity);
  if (dynamic && !desc.mass && (!std::isfinite(density) || density <= 0.0))
    fail("density must be finite and > 0 kg/m^3 (got " + std::to_string(density) + ")");

  ResolvedBody body;
  geometry::SpatialInertia fromShapes;
  bool hasFiniteShape = false;
  for (std::size_t k = 0; k < desc.shapes.size(); ++k) {
    const ShapeDesc& s = desc.shapes[k];
    const std::string where = "shapes[" + std::to_string(k) + "]";
    if (auto problem = geometry::validateShape(s.shape))
      fail(where + " (" + geometry::shapeKindName(s.shape) + "): " + *problem);
    checkPose(fail, where, s.localPose, settings.unitQuaternionTolerance);
    checkMaterial(fail, where + ".material", s.material);
    const bool isPlane = std::holds_alternative<geometry::Plane>(s.shape);
    if (isPlane && desc.motionType != MotionType::Static)
      fail(where + ": a plane is infinite; only a static body may carry it (this body is " +
           geometry::motionTypeName(desc.motionType) + ")");
    auto shape = std::make_shared<geometry::Shape>(s.shape);
    if (auto* hull = std::get_if<geometry::ConvexHull>(shape.get()); hull) {
      if (hull->triangles.empty()) {
        fail(where + ": " + kHullNeedsFaces);
      } else if (hull->faces.empty()) {  // triangles given without faces: the queries need both
        geometry::buildHullFaces(*hull);
      }
    }
    const geometry::Pose local = normalised(s.localPose);
    if (dynamic && !desc.mass && !isPlane) {
      fromShapes = fromShapes + geometry::computeMassProperties(*shape, density).transformed(local);
      hasFiniteShape = true;
    }
    body.shapes.push_back({std::move(shape), local, s.material, s.filter, s.sensor, s.userData});
  }

  if (dynamic) {
    if (desc.mass) {
      body.massProperties = *desc.mass;
      if (!desc.mass->centerOfMass.allFinite())
        fail("center_of_mass is not finite (got " + vectorText(desc.mass->centerOfMass) + ")");
    } else if (hasFiniteShape) {
      body.massProperties = fromShapes;
    } else {
      fail("a dynamic body needs finite shapes or an explicit mass and inertia");
    }
    if (auto problem = geometry::checkPhysicalValidity(body.massProperties))
      fail(*problem + (desc.mass ? "" : " (computed from the shapes at the density)"));
  }

  // Body frame = COM frame with the reference axes: shift the origin, re-express the shapes.
  const Eigen::Vector3d com = body.massProperties.centerOfMass;
  body.comPose = normalised(desc.pose) * geometry::Pose::translation(com);
  for (ResolvedShape& s : body.shapes) s.localPose.position -= com;
  return body;
}

}  // namespace coulomb::engine
