#pragma once
// Shared by the scene-loader tests: the message a scene text is refused with, and a substring
// check that prints the whole message when it fails.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <gtest/gtest.h>

#include <string>

namespace coulomb::test {

/// The CoulombError message of parsing `text` (and building its World when `build`), or
/// "(no error)".
inline std::string sceneErrorOf(const std::string& text, bool build = false) {
  try {
    const engine::io::Scene scene = engine::io::parseScene(text, "test.json");
    if (build) engine::io::buildWorld(scene);
  } catch (const engine::CoulombError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace coulomb::test

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)
