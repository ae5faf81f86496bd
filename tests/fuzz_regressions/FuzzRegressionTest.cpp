// Replays fuzz/regressions/<target>/ (inputs that once crashed or broke an invariant, kept after
// the fix) and fuzz/corpus/<target>/ (the seeds) through the entry functions the fuzzers call
// (fuzz/entries/FuzzEntries.hpp): each must hold every invariant, in the plain and sanitizer
// builds.
#include "entries/FuzzEntries.hpp"

#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

using Entry = std::string (*)(const std::uint8_t*, std::size_t);

std::vector<std::filesystem::path> inputsOf(const std::string& target) {
  std::vector<std::filesystem::path> files;
  for (const char* kind : {"regressions", "corpus"}) {
    const std::filesystem::path dir = std::filesystem::path(COULOMB_FUZZ_DIR) / kind / target;
    if (!std::filesystem::is_directory(dir)) continue;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename().string().front() != '.')
        files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());  // a stable order for reruns
  return files;
}

void replay(const std::string& target, Entry entry) {
  const std::vector<std::filesystem::path> files = inputsOf(target);
  EXPECT_FALSE(files.empty()) << "no seeds for " << target;
  for (const std::filesystem::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    ASSERT_TRUE(in) << file;
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    const std::string broken =
        entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    EXPECT_EQ(broken, "") << file;
  }
}

TEST(FuzzRegression, Scene) {
  replay("scene", coulomb::fuzz::sceneEntry);
}
TEST(FuzzRegression, Fc3d) {
  replay("fc3d", coulomb::fuzz::fc3dEntry);
}
TEST(FuzzRegression, Urdf) {
  replay("urdf", coulomb::fuzz::urdfEntry);
}
TEST(FuzzRegression, Solvers) {
  replay("solvers", coulomb::fuzz::solversEntry);
}

// Found by fuzz_scene: nlohmann's out_of_range (a number beyond double) escaped parseScene as a
// foreign exception; it is bad input like any other, a CoulombError naming the source.
TEST(FuzzRegression, JsonNumberOverflowIsACoulombError) {
  try {
    (void)coulomb::engine::io::parseScene(R"({"gravity": [0, 0, 1e999]})", "big.json");
    FAIL() << "no error";
  } catch (const coulomb::engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("big.json: invalid JSON"), std::string::npos) << e.what();
  }
}

// Found by fuzz_urdf: TinyXML 2.6.2 read past the end of text ending in a truncated UTF-8
// sequence (heap-buffer-overflow); such text is refused before TinyXML sees it, naming the line.
TEST(FuzzRegression, UrdfThatIsNotUtf8IsRefused) {
  const std::string text = "<robot name=\"r\">\n  <link name=\"a\"/>\n  <box si\xff\xda";
  try {
    (void)coulomb::engine::io::parseUrdf(text, "bad.urdf", "/nonexistent");
    FAIL() << "no error";
  } catch (const coulomb::engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.urdf:3: not UTF-8 text (byte 0xff)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
