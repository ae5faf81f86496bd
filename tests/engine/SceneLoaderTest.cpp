// The scene loader: a valid scene round-trips into a World, and every error names the source,
// the JSON path and the problem (unknown keys with the nearest known key).
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include "SceneErrorTestHelpers.hpp"

#include <string>

using namespace coulomb;
using engine::io::parseScene;

namespace {

const std::string kDataDir = COULOMB_TEST_DATA_DIR "/scenes/";

// A valid one-body scene with `body` spliced in as the body's extra members.
std::string sceneWithBody(const std::string& body) {
  return R"({"bodies": [{"name": "b", "shapes": [{"type": "sphere", "radius": 0.1}])" +
         (body.empty() ? std::string() : ", " + body) + "}]}";
}

std::string errorOf(const std::string& text, bool build = false) {
  return test::sceneErrorOf(text, build);
}

}  // namespace

TEST(SceneLoader, LoadsAValidFileIntoAWorld) {
  const engine::io::Scene scene = engine::io::loadSceneFile(kDataDir + "two_bodies.json");
  EXPECT_EQ(scene.name, "two_bodies");
  EXPECT_DOUBLE_EQ(scene.settings.timeStep, 0.005);
  EXPECT_EQ(scene.steps, 10u);
  ASSERT_EQ(scene.bodies.size(), 2u);
  EXPECT_EQ(scene.bodies[0].motionType, geometry::MotionType::Static);
  EXPECT_DOUBLE_EQ(scene.bodies[1].shapes[0].material.friction, 0.9);
  engine::World world = engine::io::buildWorld(scene);
  EXPECT_EQ(world.bodyCount(), 2u);
  EXPECT_NEAR(world.massProperties(world.findBody("ball")).mass, 1000 * 4.0 / 3 * M_PI * 1e-3,
              1e-9);
}

TEST(SceneLoader, DefaultsAndOrientationForms) {
  const auto scene = parseScene(
      R"({"bodies": [{"orientation": {"axis": [0, 0, 2], "angle": 1.0}, "mass": 2,
          "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1.5]], "center_of_mass": [0, 0, 0.1]},
          {"orientation": [0, 1, 0, 0], "type": "kinematic"}]})",
      "defaults.json");
  EXPECT_EQ(scene.name, "defaults");
  EXPECT_DOUBLE_EQ(scene.settings.gravity.z(), -9.81);
  EXPECT_EQ(scene.steps, 1000u);
  EXPECT_TRUE(scene.bodies[0].pose.rotation.isApprox(
      Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()))));
  EXPECT_DOUBLE_EQ(scene.bodies[0].mass->mass, 2.0);
  EXPECT_EQ(scene.bodies[1].motionType, geometry::MotionType::Kinematic);
}

TEST(SceneLoader, TreeIntegratorKey) {
  EXPECT_EQ(parseScene(R"({"bodies": []})", "default.json").settings.treeIntegrator,
            engine::TreeIntegrator::RungeKutta);
  EXPECT_EQ(parseScene(R"({"bodies": [], "tree_integrator": "semi_implicit_euler"})", "euler.json")
                .settings.treeIntegrator,
            engine::TreeIntegrator::SemiImplicitEuler);
  EXPECT_CONTAINS(errorOf(R"({"bodies": [], "tree_integrator": "rk4"})"),
                  "tree_integrator: must be \"runge_kutta\" or \"semi_implicit_euler\"");
}

TEST(SceneLoader, MeshFilesResolveRelativeToTheScene) {
  const engine::io::Scene scene = engine::io::loadSceneFile(kDataDir + "tetra_mesh.json");
  engine::World world = engine::io::buildWorld(scene);
  EXPECT_NEAR(world.massProperties(world.findBody("tetra")).mass, 1.0, 1e-12);  // 6 * 1/6
  EXPECT_EQ(errorOf(sceneWithBody(R"("density": 1)")), "(no error)");
  const std::string missing =
      errorOf(R"({"bodies": [{"shapes": [{"type": "mesh", "file": "no_such_file.obj"}]}]})");
  EXPECT_CONTAINS(missing, "bodies[0].shapes[0].file");
}

TEST(SceneLoader, SyntaxErrorsNameTheFile) {
  const std::string e = errorOf("{\"bodies\": [ }");
  EXPECT_CONTAINS(e, "test.json");
  EXPECT_CONTAINS(e, "invalid JSON");
  EXPECT_CONTAINS(errorOf(""), "invalid JSON");
  try {
    engine::io::loadSceneFile(kDataDir + "missing.json");
    FAIL();
  } catch (const engine::CoulombError& error) {
    EXPECT_CONTAINS(error.what(), "missing.json: cannot open");
  }
}

TEST(SceneLoader, UnknownKeysSuggestTheNearestKnownKey) {
  EXPECT_CONTAINS(errorOf(R"({"bodys": []})"),
                  "bodys: unknown key 'bodys'; did you mean 'bodies'?");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("masss": 1)")), "did you mean 'mass'?");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("lineer_velocity": [0, 0, 0])")),
                  "bodies[0].lineer_velocity");
  EXPECT_CONTAINS(
      errorOf(R"({"bodies": [{"shapes": [{"type": "sphere", "radios": 1}]}]})"),
      "bodies[0].shapes[0].radios: unknown key 'radios' for a sphere; did you mean 'radius'?");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"shapes": [{"type": "sphear", "radius": 1}]}]})"),
                  "did you mean 'sphere'?");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("type": "dinamic")")), "did you mean 'dynamic'?");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [], "zzzzzzzz": 1})"), "known keys:");
}

TEST(SceneLoader, ValueErrorsNameTheJsonPath) {
  EXPECT_CONTAINS(errorOf(R"({"time_step": -0.01, "bodies": []})"), "time_step: must be > 0");
  EXPECT_CONTAINS(errorOf(R"({"steps": 1.5, "bodies": []})"), "steps: expected a non-negative");
  EXPECT_CONTAINS(errorOf(R"({"gravity": [0, 0], "bodies": []})"),
                  "gravity: expected an array of 3");
  EXPECT_CONTAINS(errorOf(R"({"gravity": [0, "a", 0], "bodies": []})"),
                  "gravity[1]: expected a number");
  EXPECT_CONTAINS(errorOf("{}"), "bodies: missing (required)");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("mass": -1, "inertia": [1, 1, 1])")),
                  "bodies[0].mass: must be > 0 (got -1)");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("mass": 1)")), "bodies[0]: \"inertia\" is required");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("mass": 1, "inertia": [1, 1, 3])")),
                  "bodies[0].inertia: inertia breaks the triangle inequality");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("inertia": [1, 1, 1])")), "only allowed together");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("density": 0)")), "bodies[0].density: must be > 0");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("density": 1, "mass": 1, "inertia": [1,1,1])")),
                  "not both");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("orientation": [1, 1, 0, 0])")),
                  "bodies[0].orientation: quaternion [w, x, y, z] must have unit norm");
  EXPECT_CONTAINS(errorOf(sceneWithBody(R"("orientation": {"axis": [0, 0, 0], "angle": 1})")),
                  "bodies[0].orientation.axis: must be non-zero");
  EXPECT_CONTAINS(
      errorOf(R"({"bodies": [{"shapes": [{"type": "box", "half_extents": [1, 0, 1]}]}]})"),
      "bodies[0].shapes[0]: box half_extents[1] must be finite and > 0");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"shapes": [{"type": "convex_hull",
                  "points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}]}]})"),
                  "bodies[0].shapes[0]: convex_hull points are coplanar");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"shapes": [{"type": "mesh",
                  "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]],
                  "triangles": [[0,2,1],[0,1,3],[0,3,2]]}]}]})"),
                  "mesh needs at least 4 vertices and 4 triangles");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"shapes": [{"type": "mesh",
                  "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]],
                  "triangles": [[0,2,1],[0,1,3],[0,3,2],[1,2,-3]]}]}]})"),
                  "bodies[0].shapes[0].triangles[3][2]: expected a non-negative integer");
}

TEST(SceneLoader, MaterialsAndFilters) {
  EXPECT_CONTAINS(errorOf(R"({"materials": {"steel": {"friction": 0.4}}, "bodies": [{"shapes":
              [{"type": "sphere", "radius": 1, "material": "stel"}]}]})"),
                  "bodies[0].shapes[0].material: unknown material 'stel'; did you mean 'steel'?");
  EXPECT_CONTAINS(errorOf(R"({"materials": {"ice": {"friction": -1}}, "bodies": []})"),
                  "materials.ice.friction: must be >= 0");
  EXPECT_CONTAINS(errorOf(R"({"materials": {"ice": {"restitution": 2}}, "bodies": []})"),
                  "materials.ice.restitution: must be in [0, 1]");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"shapes": [{"type": "sphere", "radius": 1,
                  "filter": {"category": 4294967296}}]}]})"),
                  "filter.category: must fit in 32 bits");
  const auto scene = parseScene(R"({"bodies": [{"shapes": [{"type": "sphere", "radius": 1,
      "material": {"friction": 0.2}, "filter": {"category": 2, "mask": 5}}]}]})",
                                "ok.json");
  EXPECT_DOUBLE_EQ(scene.bodies[0].shapes[0].material.friction, 0.2);
  EXPECT_EQ(scene.bodies[0].shapes[0].filter.mask, 5u);
}

TEST(SceneLoader, WorldErrorsAreAnchoredAtTheBody) {
  // Caught by World validation (not by the parser): anchored at bodies[i].
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"name": "a", "shapes": [{"type": "plane"}]}]})", true),
                  "test.json: bodies[0].shapes[0]: a plane is infinite");
  EXPECT_CONTAINS(errorOf(R"({"bodies": [{"name": "a"}]})", true),
                  "test.json: bodies[0]: a dynamic body needs finite shapes");
}

TEST(SceneLoader, ReservedSectionsAreRefusedUntilSupported) {
  // Joints are supported (SceneJointsTest): a joint without bodies is refused at its path.
  EXPECT_CONTAINS(errorOf(R"({"bodies": [], "joints": [{"type": "hinge"}]})"),
                  "joints[0]: at least one of body_a, body_b must be a body");
  // The solver section is supported (SceneSolverSectionTest); an unknown key in it is refused.
  EXPECT_CONTAINS(errorOf(R"({"bodies": [], "solver": {"nme": "pgs"}})"),
                  "solver.nme: unknown key 'nme'");
  // URDF robots are supported (UrdfSceneTest); an entry must be an object.
  EXPECT_CONTAINS(errorOf(R"({"bodies": [], "urdf": ["robot.urdf"]})"),
                  "urdf[0]: expected an object");
}
