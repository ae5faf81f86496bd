// urdf/UrdfLoader: the corpus pitfalls (tests/data/urdf, see ORIGIN.md) are handled as
// docs/urdf.md says, malformed files give errors naming the file, line, element and a fix, and
// mesh paths resolve through the documented search path.
#include <coulomb/joints/tree/TreeDynamics.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

using namespace coulomb::engine::io;
using coulomb::engine::CoulombError;
namespace fs = std::filesystem;

std::string corpus(const std::string& relative) {
  return std::string(COULOMB_TEST_DATA_DIR) + "/urdf/" + relative;
}

bool hasWarning(const UrdfModel& model, const std::string& text) {
  return std::any_of(model.warnings.begin(), model.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

/// The CoulombError message of parsing `text` (fails the test when it loads).
std::string errorOf(const std::string& text, const UrdfOptions& options = {}) {
  try {
    parseUrdf(text, "bad.urdf", fs::path("."), options);
  } catch (const CoulombError& e) {
    return e.what();
  }
  ADD_FAILURE() << "loaded:\n" << text;
  return {};
}

const char* const kTwoLinks = R"(<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
</robot>)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(UrdfLoader, ValidSmallRobotLoads) {
  const UrdfModel model = parseUrdf(kTwoLinks, "ok.urdf", ".");
  EXPECT_EQ(model.bodies.size(), 2u);
  EXPECT_EQ(model.dofNames, std::vector<std::string>{"j"});
  EXPECT_TRUE(model.warnings.empty());
}

TEST(UrdfLoader, AcrobotIsRefusedWithTheFix) {
  try {
    loadUrdfFile(corpus("acrobot/Acrobot.urdf"));
    FAIL() << "acrobot loaded";
  } catch (const CoulombError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("Acrobot.urdf:"), std::string::npos) << m;
    EXPECT_NE(m.find("joint 'base_weld'"), std::string::npos) << m;
    EXPECT_NE(m.find("'world' is not declared"), std::string::npos) << m;
    EXPECT_NE(m.find("<link name=\"world\"/>"), std::string::npos) << m;
  }
}

TEST(UrdfLoader, MalformedFilesNameFileLineAndElement) {
  EXPECT_NE(errorOf("<robot name=\"r\"><link name=\"a\"></robot>").find("bad.urdf:1:"),
            std::string::npos);
  EXPECT_NE(errorOf(replaced(kTwoLinks, "<parent link=\"a\"/>", "<parent link=\"c\"/>"))
                .find("bad.urdf:4: joint 'j': parent link 'c' is not declared"),
            std::string::npos);
  const std::string cycle = replaced(
      kTwoLinks, "</robot>",
      "<joint name=\"k\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint></robot>");
  EXPECT_NE(errorOf(cycle).find("cycle"), std::string::npos) << errorOf(cycle);
  const std::string negative =
      errorOf(replaced(kTwoLinks, "mass value=\"1\"", "mass value=\"-2\""));
  EXPECT_NE(negative.find("bad.urdf:2: link 'a' <mass>: mass -2"), std::string::npos) << negative;
  const std::string nan = errorOf(replaced(kTwoLinks, "<axis xyz=\"0 0 1\"/>",
                                           "<origin xyz=\"nan 0 0\"/><axis xyz=\"0 0 1\"/>"));
  EXPECT_NE(nan.find("bad.urdf:4: joint 'j' <origin>: xyz=\"nan 0 0\" must be 3 finite numbers"),
            std::string::npos)
      << nan;
  const std::string planar = errorOf(replaced(kTwoLinks, "continuous", "planar"));
  EXPECT_NE(planar.find("joint 'j': type 'planar' is not supported"), std::string::npos) << planar;
  const std::string xacro = errorOf(
      "<robot xmlns:xacro=\"http://ros.org/wiki/xacro\"><xacro:include filename=\"a.xacro\"/>"
      "</robot>");
  EXPECT_NE(xacro.find("no <link> elements found. If this is a xacro file"), std::string::npos)
      << xacro;
  const std::string zeroAxis = errorOf(replaced(kTwoLinks, "0 0 1", "0 0 0"));
  EXPECT_NE(zeroAxis.find("the axis is zero"), std::string::npos) << zeroAxis;
  const std::string missing = errorOf(
      "<robot name=\"r\"><link name=\"a\"><collision><geometry>"
      "<mesh filename=\"package://p/none.stl\"/></geometry>"
      "</collision></link></robot>");
  EXPECT_NE(missing.find("mesh 'package://p/none.stl' not found"), std::string::npos) << missing;
  EXPECT_NE(missing.find("COULOMB_PACKAGE_PATH"), std::string::npos) << missing;
}

TEST(UrdfLoader, HumanoidCapsulesDroppedByUrdfdomAreReadAnyway) {
  const UrdfModel model = loadUrdfFile(corpus("humanoid/humanoid.urdf"));
  std::size_t shapes = 0, capsules = 0;
  for (const UrdfBody& body : model.bodies) {
    shapes += body.collisions.size();
    for (const UrdfCollision& c : body.collisions)
      capsules += std::holds_alternative<coulomb::geometry::Capsule>(c.shape) ? 1 : 0;
  }
  EXPECT_EQ(shapes, 19u);  // 16 capsules + 3 spheres in the file; urdfdom kept none
  EXPECT_EQ(capsules, 16u);
  EXPECT_TRUE(hasWarning(model, "urdfdom dropped <collision>"));
  EXPECT_TRUE(hasWarning(model, "urdfdom: Unknown geometry type 'capsule'"));
  EXPECT_TRUE(hasWarning(model, "joint axes normalised"));
}

TEST(UrdfLoader, PitfallPoliciesOnTheCorpus) {
  UrdfOptions noMeshes;
  noMeshes.loadCollisionMeshes = false;
  // A root named `world` is the fixed frame; pendulum's arm_com is fused into arm.
  const UrdfModel pendulum = loadUrdfFile(corpus("pendulum/Pendulum.urdf"));
  EXPECT_EQ(pendulum.frames.at("world").body, -1);
  EXPECT_EQ(pendulum.bodies.front().name, "base");
  EXPECT_NEAR(pendulum.bodies.back().inertia.mass, 1.0, 1e-15);
  // double_pendulum's <limit lower="0" upper="0"> means no limit.
  const UrdfModel dp = loadUrdfFile(corpus("double_pendulum/double_pendulum.urdf"), noMeshes);
  EXPECT_TRUE(std::isinf(dp.bodies.back().joint.upper));
  EXPECT_TRUE(hasWarning(dp, "read as unlimited"));
  // anymal_c's massless `base` gets base_inertia's mass through the fused fixed joint.
  const UrdfModel anymal = loadUrdfFile(corpus("anymal_c/anymal.urdf"));
  EXPECT_GT(anymal.bodies.front().inertia.mass, 6.0);
  EXPECT_TRUE(anymal.bodies.front().inertiaValid);
  // pr2: ten mimic joints kept as couplings, with a warning.
  const UrdfModel pr2 = loadUrdfFile(corpus("pr2/pr2.urdf"));
  EXPECT_EQ(pr2.mimics.size(), 10u);
  EXPECT_TRUE(hasWarning(pr2, "mimic joints are kept as couplings"));
  EXPECT_TRUE(hasWarning(pr2, "links without <inertial>"));
  // Floating base: 6 more velocity coordinates, quaternion first at identity.
  UrdfOptions floating = noMeshes;
  floating.base = UrdfBase::Floating;
  const auto solo = toArticulation(loadUrdfFile(corpus("solo12/solo12.urdf"), floating));
  EXPECT_TRUE(solo.hasFloatingBase());
  EXPECT_EQ(solo.nv(), 18);
  EXPECT_EQ(solo.nq(), 19);
  const Eigen::VectorXd qdd = coulomb::joints::tree::forwardDynamics(
      solo, solo.neutralConfiguration(), Eigen::VectorXd::Zero(18), Eigen::VectorXd::Zero(18));
  EXPECT_TRUE(qdd.allFinite());
  EXPECT_NEAR(qdd.head<6>().tail<3>().norm(), 9.81, 1e-9);  // free fall of the whole robot
}

TEST(UrdfLoader, MasslessSubtreeGetsATinyInertiaNotANan) {
  const std::string text =
      replaced(kTwoLinks,
               "<link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" "
               "izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>",
               "<link name=\"b\"/>");
  const UrdfModel model = parseUrdf(text, "massless.urdf", ".");
  EXPECT_TRUE(hasWarning(model, "nothing massive behind them"));
  const auto tree = toArticulation(model);
  const Eigen::VectorXd qdd = coulomb::joints::tree::forwardDynamics(
      tree, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1));
  EXPECT_TRUE(qdd.allFinite());
}

class UrdfMeshPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("coulomb_urdf_paths_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "robot" / "urdf");
    fs::create_directories(dir_ / "share" / "my_pkg" / "meshes");
    std::ofstream(dir_ / "share" / "my_pkg" / "meshes" / "tet.stl") << R"(solid t
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 0 1 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 1 0 0
  vertex 0 1 0
  vertex 0 0 1
 endloop
endfacet
endsolid t
)";
    std::ofstream(dir_ / "robot" / "urdf" / "r.urdf")
        << R"(<robot name="r"><link name="a"><collision><geometry>
<mesh filename="package://my_pkg/meshes/tet.stl" scale="2 2 2"/></geometry></collision></link></robot>)";
  }
  void TearDown() override {
    unsetenv("COULOMB_PACKAGE_PATH");
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(UrdfMeshPaths, PackageUrisResolveThroughOptionAndEnvironment) {
  const fs::path urdf = dir_ / "robot" / "urdf" / "r.urdf";
  EXPECT_THROW(loadUrdfFile(urdf), CoulombError);
  UrdfOptions options;
  options.packagePath = {dir_ / "share"};
  const UrdfModel viaOption = loadUrdfFile(urdf, options);
  ASSERT_EQ(viaOption.bodies.front().collisions.size(), 1u);
  const auto& hull =
      std::get<coulomb::geometry::ConvexHull>(viaOption.bodies.front().collisions.front().shape);
  EXPECT_EQ(hull.vertices.size(), 4u);
  double maxCoordinate = 0.0;
  for (const Eigen::Vector3d& v : hull.vertices)
    maxCoordinate = std::max(maxCoordinate, v.maxCoeff());
  EXPECT_DOUBLE_EQ(maxCoordinate, 2.0);  // scale applied
  const std::string path = (dir_ / "nowhere").string() + ":" + (dir_ / "share").string();
  setenv("COULOMB_PACKAGE_PATH", path.c_str(), 1);
  EXPECT_EQ(loadUrdfFile(urdf).bodies.front().collisions.size(), 1u);
}

}  // namespace
