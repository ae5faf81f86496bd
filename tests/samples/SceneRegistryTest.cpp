#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>

#include "scenes/SceneRegistry.hpp"

using namespace coulomb;

TEST(SceneRegistry, ListsTheBuiltinScenesSorted) {
  std::vector<std::string> names;
  for (const auto& s : scenes::builtinScenes()) names.emplace_back(s.name);
  for (const char* expected : {"dzhanibekov", "projectile", "symmetric_top"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
}

TEST(SceneRegistry, EveryBuiltinSceneLoadsAndBuilds) {
  for (const auto& s : scenes::builtinScenes()) {
    const auto scene = scenes::loadBuiltinScene(s.name);
    EXPECT_EQ(scene.name, s.name);
    EXPECT_FALSE(scene.description.empty()) << s.name;
    EXPECT_NO_THROW(engine::io::buildWorld(scene)) << s.name;
  }
}

TEST(SceneRegistry, UnknownNamesSuggestTheNearest) {
  try {
    scenes::loadBuiltinScene("dzanibekov");
    FAIL();
  } catch (const engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'dzhanibekov'?"), std::string::npos);
  }
  EXPECT_THROW(scenes::resolveScene("/no/such/scene.json"), engine::CoulombError);
  EXPECT_NO_THROW(scenes::resolveScene(COULOMB_TEST_DATA_DIR "/scenes/two_bodies.json"));
}
