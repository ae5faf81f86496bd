#pragma once
// The fuzz entry functions (docs/reliability.md, "Fuzzing"): each takes one fuzz input and returns
// "" when every documented invariant held, else what broke. Input a loader refuses with a
// CoulombError (or an error result) is fine; a crash, a sanitizer report, any other exception, or
// a NaN where the documentation promises none is not. libFuzzer calls them through FuzzMain.cpp;
// tests/fuzz_regressions replays fuzz/regressions/<target>/ through them in every build.
#include <cstddef>
#include <cstdint>
#include <string>

namespace coulomb::fuzz {

// JSON scene text: engine::io::parseScene, buildWorld, then a few steps of a small world.
std::string sceneEntry(const std::uint8_t* data, std::size_t size);
// fc3d-text: solvers::parseFc3dText, then validate() and one bounded pgs solve of a small problem.
std::string fc3dEntry(const std::uint8_t* data, std::size_t size);
// URDF text: engine::io::parseUrdf (meshes not read), toArticulation, toArticulationDesc.
std::string urdfEntry(const std::uint8_t* data, std::size_t size);
// Bytes decoded into a small ContactProblem (SolversEntry.cpp), validate() and every registered
// solver with a bounded iteration count.
std::string solversEntry(const std::uint8_t* data, std::size_t size);

}  // namespace coulomb::fuzz
