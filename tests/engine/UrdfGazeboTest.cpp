// urdf/UrdfGazebo: <gazebo> extensions as robot descriptions write them (docs/urdf.md,
// "Gazebo extensions"). Values come from the element text or a `value` attribute; an invalid value
// is a warning naming file:line that drops that value; nothing in a <gazebo> block fails a load.
// Fixtures: tests/data/urdf/gazebo (ours, see ORIGIN.md there).
#include <coulomb/io/UrdfReport.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

namespace {

using namespace coulomb::engine::io;
namespace fs = std::filesystem;

std::string fixture(const std::string& name) {
  return std::string(COULOMB_TEST_DATA_DIR) + "/urdf/gazebo/" + name;
}

UrdfOptions withoutMeshes(double defaultFriction = 0.8) {
  UrdfOptions options;
  options.loadCollisionMeshes = false;
  options.defaultFriction = defaultFriction;
  return options;
}

std::vector<std::string> warningsWith(const UrdfModel& model, const std::string& text) {
  std::vector<std::string> out;
  std::copy_if(model.warnings.begin(), model.warnings.end(), std::back_inserter(out),
               [&](const std::string& w) { return w.find(text) != std::string::npos; });
  return out;
}

/// Friction of every collider, by the URDF link that declared it.
std::map<std::string, double> frictionByLink(const UrdfModel& model) {
  std::map<std::string, double> out;
  for (const UrdfBody& body : model.bodies)
    for (const UrdfCollision& c : body.collisions) out[c.link] = c.material.friction;
  return out;
}

int countOf(const std::map<std::string, int>& counts, const std::string& name) {
  const auto it = counts.find(name);
  return it == counts.end() ? 0 : it->second;
}

TEST(UrdfGazebo, QuadrupedWithFrictionInElementTextLoads) {
  const std::string file = fixture("quadruped.urdf");
  const UrdfModel model = loadUrdfFile(file, withoutMeshes());
  EXPECT_EQ(model.dofCount(), 12);
  EXPECT_EQ(model.gazebo.blocks, 27);
  // <mu1>0.6</mu1> on the feet, 0.2 on the trunk and the leg links: every collider has its link's.
  const std::map<std::string, double> friction = frictionByLink(model);
  EXPECT_EQ(friction.size(), 17u);  // trunk + 4 x (hip, thigh, calf, foot)
  for (const auto& [link, mu] : friction) {
    const bool foot = link.size() > 5 && link.compare(link.size() - 5, 5, "_foot") == 0;
    EXPECT_DOUBLE_EQ(mu, foot ? 0.6 : 0.2) << link;
    EXPECT_DOUBLE_EQ(model.gazebo.friction.at(link), mu) << link;
  }
  EXPECT_EQ(countOf(model.gazebo.used, "mu1"), 17);
  EXPECT_EQ(countOf(model.gazebo.used, "mu2"), 17);  // equal to mu1: an isotropic cone
  EXPECT_EQ(countOf(model.gazebo.ignored, "kp"), 17);
  EXPECT_EQ(countOf(model.gazebo.ignored, "kd"), 17);
  EXPECT_EQ(countOf(model.gazebo.ignored, "selfCollide"), 1);
  EXPECT_EQ(countOf(model.gazebo.ignored, "self_collide"), 16);
  EXPECT_EQ(countOf(model.gazebo.ignored, "plugin"), 2);  // ros_control, trajectory plot
  EXPECT_EQ(countOf(model.gazebo.ignored, "sensor"), 5);  // IMU, four foot contacts
  EXPECT_EQ(countOf(model.gazebo.ignored, "turnGravityOff"), 1);
  // The one real problem: a block for a link the file does not declare (line 99).
  const auto stale = warningsWith(model, "<gazebo");
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0], file +
                          ":99: <gazebo reference=\"stick_link\">: no link or joint is named "
                          "'stick_link'; the block is ignored");
}

TEST(UrdfGazebo, HumanoidWithDozensOfBlocksLoads) {
  const UrdfModel model = loadUrdfFile(fixture("humanoid.urdf"), withoutMeshes(0.5));
  EXPECT_EQ(model.dofCount(), 24);
  EXPECT_EQ(model.gazebo.blocks, 38);
  const std::map<std::string, double> friction = frictionByLink(model);
  EXPECT_DOUBLE_EQ(friction.at("left_foot_link"), 1.0);   // <mu1>1.0</mu1>
  EXPECT_DOUBLE_EQ(friction.at("right_foot_link"), 1.0);  // <mu1>1.0</mu1>
  EXPECT_DOUBLE_EQ(friction.at("left_hand_link"), 0.8);   // <mu1 value="0.8"/>
  EXPECT_DOUBLE_EQ(friction.at("right_hand_link"), 0.8);
  EXPECT_DOUBLE_EQ(friction.at("torso"), 0.5);  // no <mu1>: the default
  EXPECT_EQ(model.gazebo.friction.size(), 4u);
  EXPECT_EQ(countOf(model.gazebo.ignored, "material"), 30);
  EXPECT_EQ(countOf(model.gazebo.ignored, "selfCollide"), 28);
  EXPECT_EQ(countOf(model.gazebo.ignored, "turnGravityOff"), 23);
  EXPECT_EQ(countOf(model.gazebo.ignored, "provideFeedback"), 2);       // blocks of joints
  EXPECT_EQ(countOf(model.gazebo.ignored, "implicitSpringDamper"), 2);  // blocks of joints
  EXPECT_EQ(countOf(model.gazebo.ignored, "sensor"), 2);
  EXPECT_EQ(countOf(model.gazebo.ignored, "plugin"), 2);
  EXPECT_TRUE(warningsWith(model, "<gazebo").empty()) << warningsWith(model, "<gazebo")[0];
}

const char* const kOneLink = R"(<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <link name="b">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
)";

/// kOneLink plus `gazebo` from line 11 on.
UrdfModel parseWith(const std::string& gazebo) {
  return parseUrdf(std::string(kOneLink) + gazebo + "</robot>", "g.urdf", fs::path("."),
                   withoutMeshes(0.5));
}

TEST(UrdfGazebo, ValueAttributeAndTextAreBothRead) {
  EXPECT_DOUBLE_EQ(
      frictionByLink(parseWith("<gazebo reference=\"a\"><mu1>0.3</mu1></gazebo>"))["a"], 0.3);
  EXPECT_DOUBLE_EQ(
      frictionByLink(parseWith("<gazebo reference=\"a\"><mu1> 0.3\n </mu1></gazebo>"))["a"], 0.3);
  EXPECT_DOUBLE_EQ(
      frictionByLink(parseWith("<gazebo reference=\"a\"><mu1 value=\"0.4\"/></gazebo>"))["a"], 0.4);
  // Both: the attribute, as Gazebo's URDF converter reads it.
  EXPECT_DOUBLE_EQ(frictionByLink(parseWith(
                       "<gazebo reference=\"a\"><mu1 value=\"0.4\">0.9</mu1></gazebo>"))["a"],
                   0.4);
  // Several blocks for one link: the last valid value.
  const UrdfModel twice = parseWith(
      "<gazebo reference=\"b\"><mu1>0.3</mu1></gazebo>\n<gazebo reference=\"b\"><mu1>0.7</mu1>"
      "</gazebo>");
  EXPECT_DOUBLE_EQ(frictionByLink(twice)["b"], 0.7);
  EXPECT_DOUBLE_EQ(frictionByLink(twice)["a"], 0.5);
}

TEST(UrdfGazebo, InvalidValuesAreWarningsWithFileAndLineAndAreDropped) {
  struct Case {
    std::string value, problem;
  };
  for (const Case& c :
       {Case{"<mu1>-0.2</mu1>", "-0.2 is negative"},
        Case{"<mu1>nan</mu1>", "'nan' is not a finite number"},
        Case{"<mu1 value=\"inf\"/>", "'inf' is not a finite number"},
        Case{"<mu1>high</mu1>", "'high' is not a number"},
        Case{"<mu1>0.2 0.3</mu1>", "'0.2 0.3' is not a number"},
        Case{"<mu1>1e999</mu1>", "'1e999' is not a finite number"}, Case{"<mu1/>", "no value"}}) {
    const UrdfModel model = parseWith("<gazebo reference=\"b\">\n  " + c.value + "\n</gazebo>");
    const auto warnings = warningsWith(model, "<gazebo");
    ASSERT_EQ(warnings.size(), 1u) << c.value;
    EXPECT_EQ(warnings[0].rfind("g.urdf:12: <gazebo reference=\"b\"> <mu1>: " + c.problem, 0), 0u)
        << warnings[0];
    EXPECT_NE(warnings[0].find("this value is dropped"), std::string::npos) << warnings[0];
    EXPECT_DOUBLE_EQ(frictionByLink(model)["b"], 0.5) << c.value;  // the default
    EXPECT_EQ(countOf(model.gazebo.ignored, "mu1"), 1) << c.value;
  }
  // Only the invalid value goes: an earlier valid one stays, and so do the block's others.
  const UrdfModel kept = parseWith(
      "<gazebo reference=\"b\"><mu1>0.3</mu1></gazebo>\n"
      "<gazebo reference=\"b\"><mu1>-1</mu1><mu2>0.3</mu2></gazebo>\n"
      "<gazebo reference=\"a\"><mu1>abc</mu1></gazebo><gazebo reference=\"a\"><mu1>0.6</mu1>"
      "</gazebo>");
  EXPECT_DOUBLE_EQ(frictionByLink(kept)["b"], 0.3);
  EXPECT_DOUBLE_EQ(frictionByLink(kept)["a"], 0.6);
  EXPECT_EQ(countOf(kept.gazebo.used, "mu2"), 1);
  EXPECT_EQ(warningsWith(kept, "<gazebo").size(), 2u);
}

TEST(UrdfGazebo, UnsupportedChildrenNeverFailALoad) {
  const UrdfModel model = parseWith(R"(
<gazebo><plugin name="p" filename="libp.so"><any>thing</any></plugin><static>false</static></gazebo>
<gazebo reference="j"><provideFeedback>true</provideFeedback><stopCfm>-3</stopCfm></gazebo>
<gazebo reference="a">
  <kp value="-5"/><kd>nan</kd><maxVel>x</maxVel><selfCollide>false</selfCollide>
  <sensor name="s" type="contact"><contact><collision>a_collision</collision></contact></sensor>
  <material>Gazebo/Red</material><visual><material><ambient>1 0 0 1</ambient></material></visual>
  <mu2>0.9</mu2>
</gazebo>
<gazebo reference="b"><mu1>0.4</mu1><mu2>0.2</mu2><turnGravityOff>true</turnGravityOff></gazebo>)");
  EXPECT_EQ(model.gazebo.blocks, 4);
  for (const char* element :
       {"plugin", "static", "provideFeedback", "stopCfm", "kp", "kd", "maxVel", "selfCollide",
        "sensor", "material", "visual", "turnGravityOff"})
    EXPECT_EQ(countOf(model.gazebo.ignored, element), 1) << element;
  EXPECT_EQ(countOf(model.gazebo.ignored, "mu2"), 2);
  EXPECT_EQ(frictionByLink(model)["b"], 0.4);
  EXPECT_EQ(frictionByLink(model)["a"], 0.5);
  // Values of ignored children are not judged (kp -5, kd nan); an anisotropic or lone mu2 and a
  // link without gravity change the motion, so they are said.
  const auto warnings = warningsWith(model, "<gazebo");
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(warnings[0],
            "g.urdf: <gazebo> switches gravity off (turnGravityOff true or gravity false) for 1 "
            "link(s); ignored, Coulomb applies gravity to every body: b (line 20)");
  EXPECT_NE(warnings[1].find("g.urdf:18: <gazebo reference=\"a\"> <mu2>: no <mu1> for this link"),
            std::string::npos)
      << warnings[1];
  EXPECT_NE(warnings[2].find("g.urdf:20: <gazebo reference=\"b\"> <mu2>: 0.2 differs from <mu1> "
                             "0.4; ignored"),
            std::string::npos)
      << warnings[2];
}

TEST(UrdfGazebo, InfoListsWhatWasUsedAndWhatWasIgnored) {
  const UrdfModel model = loadUrdfFile(fixture("quadruped.urdf"), withoutMeshes());
  const std::string text = urdfInfoText(model);
  EXPECT_NE(text.find("gazebo extensions (27 <gazebo> blocks):\n  used: mu1 x17, mu2 x17\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("FR_foot 0.6"), std::string::npos) << text;
  EXPECT_NE(text.find("  ignored: gravity x1, kd x17, kp x17, material x15, plugin x2, "
                      "selfCollide x1, self_collide x16, sensor x5, turnGravityOff x1\n"),
            std::string::npos)
      << text;
  const nlohmann::json json = nlohmann::json::parse(urdfInfoJson(model));
  EXPECT_EQ(json["gazebo"]["blocks"], 27);
  EXPECT_EQ(json["gazebo"]["friction"]["RL_foot"], 0.6);
  EXPECT_EQ(json["gazebo"]["used"]["mu1"], 17);
  EXPECT_EQ(json["gazebo"]["ignored"]["plugin"], 2);
  // A file without <gazebo> says nothing about it in text.
  const UrdfModel plain = parseWith("");
  EXPECT_EQ(urdfInfoText(plain).find("gazebo"), std::string::npos);
}

}  // namespace
