// The inertia policy of reduced coordinates (docs/urdf.md, "Inertia policy"): a tree needs only
// positive (semi)definite link inertias, so the loader keeps a tensor that breaks the triangle
// inequality as the file writes it (with a warning) and repairs only what ABA cannot use.
// `urdf dynamics` must then compute with what the file says: its qddot on
// tests/data/urdf/mechanisms/hand_cad.urdf is checked against a Newton-Euler recomputation
// written here from the file's numbers (no engine code).
#include <coulomb/engine/World.hpp>
#include <coulomb/io/UrdfReport.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>
#include <coulomb/urdf/UrdfMaximal.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace coulomb::engine::io;
using Eigen::Matrix3d;
using Eigen::Vector3d;

std::string handFile() {
  return std::string(COULOMB_TEST_DATA_DIR) + "/urdf/mechanisms/hand_cad.urdf";
}

// ---- An independent model of hand_cad.urdf: its numbers copied from the file ----------------

struct Link {
  const char* name;
  int parent;            // index in kHand, -1 = the welded palm's parent (the world)
  bool moving;           // revolute (true) or fixed
  Vector3d xyz, rpy;     // <joint><origin>
  Vector3d axis;         // <axis>
  double mass;           // <mass>
  Vector3d com, comRpy;  // <inertial><origin>
  double ixx, iyy, izz, ixy, ixz, iyz;
};

const std::vector<Link> kHand = {
    {"palm",
     -1,
     false,
     {0, 0, 0},
     {0, 0, 0},
     {0, 0, 0},
     0.35,
     {0.012, 0.006, 0.048},
     {0, 0, 0},
     2.2324e-4,
     2.9437e-4,
     5.8239e-4,
     -1.6981e-5,
     -1.7163e-5,
     -1.2603e-4},
    {"thumb_proximal",
     0,
     true,
     {0.021, -0.018, 0.032},
     {0.35, -0.52, 0.78},
     {0.6, 0, 0.8},
     0.022,
     {0.0015, 0.002, 0.019},
     {0.1, -0.2, 0.3},
     1.1899e-6,
     2.6149e-6,
     2.5952e-6,
     -9.3745e-8,
     2.6863e-7,
     -1.2707e-6},
    {"thumb_distal",
     1,
     true,
     {0.0, 0.004, 0.041},
     {0, 0.12, -0.05},
     {0, 1, 0},
     0.012,
     {-0.001, 0.0012, 0.014},
     {0, 0, 0},
     1.4318e-6,
     1.5237e-6,
     1.3445e-6,
     5.8886e-7,
     5.8419e-7,
     5.7207e-7},
    {"index_proximal",
     0,
     true,
     {0.028, 0.024, 0.095},
     {0.05, 0.08, -0.1},
     {0, 1, 0},
     0.025,
     {0.002, -0.0008, 0.022},
     {0, 0, 0},
     2.0034e-6,
     1.8629e-6,
     3.3337e-6,
     4.4530e-7,
     1.0464e-6,
     1.0286e-6},
    {"index_middle",
     3,
     true,
     {0.001, 0, 0.044},
     {0, 0, 0.03},
     {0, 1, 0},
     0.014,
     {0.0011, 0.0004, 0.013},
     {0, 0, 0},
     9.6015e-7,
     2.6434e-6,
     1.1965e-6,
     -2.7301e-7,
     5.4912e-8,
     -6.0168e-7},
    {"index_distal",
     4,
     true,
     {0, -0.001, 0.027},
     {0.02, 0, 0},
     {0, 0.8, 0.6},
     0.009,
     {0.0006, 0, 0.009},
     {-0.25, 0.15, 0},
     5.9864e-7,
     1.1228e-6,
     1.0786e-6,
     -2.2573e-7,
     -1.4884e-7,
     5.3453e-7},
    {"index_tip",
     5,
     false,
     {0.002, 0, 0.021},
     {0, 0.3, 0},
     {0, 0, 0},
     0.003,
     {0, 0.0005, 0.003},
     {0, 0, 0},
     2.3664e-7,
     3.4707e-7,
     5.6628e-7,
     3.9974e-8,
     -2.0188e-8,
     -2.1372e-7},
    {"middle_proximal",
     0,
     true,
     {0.004, 0.026, 0.099},
     {-0.04, 0.02, 0.06},
     {0, 1, 0},
     0.027,
     {0.0018, 0.001, 0.024},
     {0, 0, 0},
     2.8571e-6,
     1.7174e-6,
     3.2255e-6,
     4.2463e-7,
     -1.5669e-6,
     -6.2157e-7},
    {"middle_distal",
     7,
     true,
     {0, 0.0015, 0.048},
     {0, -0.07, 0},
     {0, 0.96, 0.28},
     0.016,
     {0.0009, -0.0005, 0.016},
     {0, 0, 0},
     9.6198e-7,
     1.4652e-6,
     1.3728e-6,
     4.4595e-7,
     -3.5463e-7,
     -6.3792e-7},
};

// DOF order of the file (every joint's parent comes first).
const std::vector<std::string> kJoints = {"thumb_cmc", "thumb_ip",   "index_mcp", "index_pip",
                                          "index_dip", "middle_mcp", "middle_pip"};

Matrix3d rpyMatrix(const Vector3d& rpy) {  // URDF: R = Rz(yaw) Ry(pitch) Rx(roll)
  return (Eigen::AngleAxisd(rpy.z(), Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Vector3d::UnitX()))
      .toRotationMatrix();
}

Matrix3d tensor(const Link& l) {
  Matrix3d i;
  i << l.ixx, l.ixy, l.ixz, l.ixy, l.iyy, l.iyz, l.ixz, l.iyz, l.izz;
  return i;
}

/// Joint torques by the recursive Newton-Euler algorithm in world coordinates (Craig's form:
/// forces at each COM, moments summed about each joint origin), gravity as a base acceleration.
Eigen::VectorXd newtonEuler(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                            const Eigen::VectorXd& qdd, const Vector3d& gravity) {
  const std::size_t n = kHand.size();
  std::vector<Matrix3d> rotation(n);
  std::vector<Vector3d> origin(n), axis(n), omega(n), alpha(n), accel(n), force(n), moment(n);
  std::vector<int> dof(n, -1);
  int next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Link& l = kHand[i];
    if (l.moving) dof[i] = next++;
    if (l.parent < 0) {  // the palm, welded to the world at the identity
      rotation[i] = Matrix3d::Identity();
      origin[i] = omega[i] = alpha[i] = Vector3d::Zero();
      accel[i] = -gravity;
      continue;
    }
    const auto p = static_cast<std::size_t>(l.parent);
    const Matrix3d jointFrame = rotation[p] * rpyMatrix(l.rpy);
    const double qi = l.moving ? q[dof[i]] : 0.0, qdi = l.moving ? qd[dof[i]] : 0.0,
                 qddi = l.moving ? qdd[dof[i]] : 0.0;
    const Vector3d a = l.moving ? l.axis.normalized() : Vector3d::UnitZ();
    axis[i] = jointFrame * a;
    rotation[i] = jointFrame * Eigen::AngleAxisd(qi, a).toRotationMatrix();
    origin[i] = origin[p] + rotation[p] * l.xyz;
    const Vector3d r = origin[i] - origin[p];
    omega[i] = omega[p] + axis[i] * qdi;
    alpha[i] = alpha[p] + axis[i] * qddi + omega[p].cross(axis[i] * qdi);
    accel[i] = accel[p] + alpha[p].cross(r) + omega[p].cross(omega[p].cross(r));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Link& l = kHand[i];
    const Vector3d c = rotation[i] * l.com;
    const Matrix3d inertialFrame = rotation[i] * rpyMatrix(l.comRpy);
    const Matrix3d inertia = inertialFrame * tensor(l) * inertialFrame.transpose();
    const Vector3d accelCom = accel[i] + alpha[i].cross(c) + omega[i].cross(omega[i].cross(c));
    force[i] = l.mass * accelCom;
    moment[i] = inertia * alpha[i] + omega[i].cross(inertia * omega[i]) + c.cross(force[i]);
  }
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(next);
  for (std::size_t i = n; i-- > 1;) {  // children after parents: accumulate backwards
    const auto p = static_cast<std::size_t>(kHand[i].parent);
    if (dof[i] >= 0) tau[dof[i]] = axis[i].dot(moment[i]);
    force[p] += force[i];
    moment[p] += moment[i] + (origin[i] - origin[p]).cross(force[i]);
  }
  return tau;
}

/// qddot = M^-1 (tau - h): M column by column from Newton-Euler with unit accelerations and no
/// gravity or velocity (the composite idea without its algorithm), h with both.
Eigen::VectorXd referenceQddot(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               const Eigen::VectorXd& tau, const Vector3d& gravity) {
  const auto nv = q.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nv);
  Eigen::MatrixXd mass(nv, nv);
  for (Eigen::Index j = 0; j < nv; ++j)
    mass.col(j) = newtonEuler(q, zero, Eigen::VectorXd::Unit(nv, j), Vector3d::Zero());
  const Eigen::VectorXd bias = newtonEuler(q, qd, zero, gravity);
  return mass.ldlt().solve(tau - bias);
}

struct State {
  Eigen::VectorXd q{{0.4, -0.3, 0.7, 0.5, 0.25, -0.2, 0.9}};
  Eigen::VectorXd qd{{1.5, -2.0, 0.8, 3.1, -1.2, 2.4, -0.7}};
  Eigen::VectorXd tau{{0.002, -0.001, 0.003, 0.0015, -0.0005, 0.001, 0.0008}};
  Vector3d gravity{0.3, -9.5, -2.1};  // a tilted hand
};

std::string stateJson(const State& s) {
  nlohmann::json j;
  for (std::size_t k = 0; k < kJoints.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    j["q"][kJoints[k]] = s.q[i];
    j["qdot"][kJoints[k]] = s.qd[i];
    j["tau"][kJoints[k]] = s.tau[i];
  }
  j["gravity"] = {s.gravity.x(), s.gravity.y(), s.gravity.z()};
  return j.dump();
}

double relativeError(const Eigen::VectorXd& value, const Eigen::VectorXd& reference) {
  return (value - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

// ---- Tests -------------------------------------------------------------------------------------

TEST(UrdfInertiaPolicy, ReferenceModelIsWhatTheTestClaims) {
  // Every tensor of the copy is positive definite and breaks the triangle inequality.
  for (const Link& l : kHand) {
    const Vector3d m = Eigen::SelfAdjointEigenSolver<Matrix3d>(tensor(l)).eigenvalues();
    EXPECT_GT(m[0], 0.0) << l.name;
    EXPECT_LT(m[0] + m[1], 0.9 * m[2]) << l.name;
  }
  // The reference's own consistency: tau of its qddot is the tau it was given.
  const State s;
  const Eigen::VectorXd qdd = referenceQddot(s.q, s.qd, s.tau, s.gravity);
  EXPECT_LT((newtonEuler(s.q, s.qd, qdd, s.gravity) - s.tau).norm(), 1e-15);
}

TEST(UrdfInertiaPolicy, UrdfDynamicsMatchesNewtonEulerFromTheFile) {
  const UrdfModel model = loadUrdfFile(handFile(), urdfDynamicsOptions());
  ASSERT_EQ(model.dofNames, kJoints);
  const State s;
  const UrdfJointState state = parseUrdfJointState(stateJson(s), "state.json", model);
  const nlohmann::json out = nlohmann::json::parse(urdfDynamicsJson(model, state));
  const std::vector<double> qddot = out["qddot"];
  const Eigen::VectorXd ours = Eigen::Map<const Eigen::VectorXd>(qddot.data(), 7);
  const Eigen::VectorXd reference = referenceQddot(s.q, s.qd, s.tau, s.gravity);
  const double error = relativeError(ours, reference);
  std::cout << "hand_cad qddot: max relative error " << error << " (max |qddot| "
            << reference.cwiseAbs().maxCoeff() << " rad/s^2)\n";
  EXPECT_LT(error, 1e-10) << "ours " << ours.transpose() << "\nreference " << reference.transpose();
  // The output says the numbers are the file's; the bodies that are not physical are named.
  EXPECT_EQ(out["inertias"]["as_written"], true);
  EXPECT_TRUE(out["inertias"]["repaired"].empty());
  // 8 bodies; index_distal with its fused tip happens to be physical, the 7 others are not.
  EXPECT_EQ(out["inertias"]["not_physical_kept"].size(), 7u);
}

TEST(UrdfInertiaPolicy, TensorsBreakingTheTriangleInequalityAreKeptWithAWarning) {
  const UrdfModel model = loadUrdfFile(handFile(), urdfDynamicsOptions());
  for (const UrdfBody& body : model.bodies) {
    const auto link = std::find_if(kHand.begin(), kHand.end(),
                                   [&](const Link& l) { return body.name == l.name; });
    ASSERT_NE(link, kHand.end()) << body.name;
    if (!body.fusedLinks.empty()) continue;  // index_distal + index_tip: a sum, checked above
    EXPECT_EQ(body.inertiaStatus, UrdfInertiaStatus::AsWritten) << body.name;
    const Matrix3d r = rpyMatrix(link->comRpy);
    EXPECT_TRUE(body.inertia.inertiaAboutCom.isApprox(r * tensor(*link) * r.transpose(), 1e-15))
        << body.name;  // the file's tensor, turned by <inertial><origin rpy> only
  }
  const auto warning = std::find_if(
      model.warnings.begin(), model.warnings.end(),
      [](const std::string& w) { return w.find("triangle inequality") != std::string::npos; });
  ASSERT_NE(warning, model.warnings.end());
  EXPECT_NE(warning->find("kept as written"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("thumb_proximal (moments"), std::string::npos) << *warning;
  EXPECT_NE(urdfInfoText(model).find("inertia as written, not physical"), std::string::npos);
}

/// A palm and one finger whose tensor is indefinite: ixy = 2e-6 on a diagonal of 1e-6 gives
/// principal moments (-1e-6, 1e-6, 3e-6). No algorithm can use it.
const char* const kIndefinite = R"(<robot name="bad_cad">
  <link name="palm">
    <inertial><mass value="0.35"/><inertia ixx="2e-4" iyy="3e-4" izz="4e-4" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="finger">
    <inertial>
      <origin xyz="0 0.002 0.02"/>
      <mass value="0.02"/>
      <inertia ixx="1e-6" iyy="1e-6" izz="1e-6" ixy="2e-6" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="knuckle" type="revolute">
    <origin xyz="0.01 0 0.09" rpy="0.1 0 0"/><parent link="palm"/><child link="finger"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>)";

TEST(UrdfInertiaPolicy, TensorThatIsNotSemidefiniteIsStillRepairedWithAWarning) {
  const UrdfModel model =
      parseUrdf(kIndefinite, "bad_cad.urdf", std::filesystem::path("."), urdfDynamicsOptions());
  const UrdfBody& finger = model.bodies.back();
  EXPECT_EQ(finger.inertiaStatus, UrdfInertiaStatus::Repaired);
  const Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Matrix3d>(finger.inertia.inertiaAboutCom).eigenvalues();
  EXPECT_NEAR(moments[0], 3e-15, 1e-20);  // lifted to the floor, 1e-9 of the largest
  EXPECT_NEAR(moments[1], 1e-6, 1e-18);   // the usable moments are kept
  EXPECT_NEAR(moments[2], 3e-6, 1e-18);
  const auto warning =
      std::find_if(model.warnings.begin(), model.warnings.end(), [](const std::string& w) {
        return w.find(
                   "body 'finger': inertia not positive "
                   "semidefinite") != std::string::npos;
      });
  EXPECT_NE(warning, model.warnings.end());
  // urdf dynamics runs, and says that this body is not the file's.
  const UrdfJointState state = parseUrdfJointState(R"({"q": {"knuckle": 0.3}})", "s.json", model);
  const nlohmann::json out = nlohmann::json::parse(urdfDynamicsJson(model, state));
  EXPECT_TRUE(std::isfinite(out["qddot"][0].get<double>()));
  EXPECT_EQ(out["inertias"]["as_written"], false);
  EXPECT_EQ(out["inertias"]["repaired"], nlohmann::json::array({"finger"}));
}

}  // namespace

TEST(UrdfInertiaPolicy, FreeBodiesOfTheMaximalFormKeepTheRepair) {
  // A free rigid body must be one a mass distribution has (World::createBody refuses the
  // others), so toMaximal lifts the tensors the tree keeps, says so, and the World takes them.
  const UrdfModel model = loadUrdfFile(handFile(), urdfDynamicsOptions());
  const UrdfMaximal robot = toMaximal(model, "hand");
  int lifted = 0;
  for (const std::string& w : robot.warnings)
    lifted += w.find("(triangle inequality)") != std::string::npos ? 1 : 0;
  EXPECT_EQ(lifted, 6);  // the 7 the tree keeps as written but the palm, static here
  for (const coulomb::engine::BodyDesc& body : robot.bodies) {
    if (body.mass) {
      EXPECT_FALSE(coulomb::geometry::checkPhysicalValidity(*body.mass).has_value()) << body.name;
    }
  }
  coulomb::engine::World world;
  EXPECT_EQ(createMaximal(world, robot).bodies.size(), model.bodies.size());
  // The tree's own articulation in a World takes the file's tensors as they are.
  coulomb::engine::World reduced;
  EXPECT_NO_THROW(reduced.createArticulation(toArticulationDesc(model, "hand")));
}
