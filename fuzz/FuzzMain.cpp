// The libFuzzer driver of one target (fuzz/CMakeLists.txt compiles it once per entry function):
// a broken invariant aborts, so libFuzzer keeps the input as a crash.
#include "entries/FuzzEntries.hpp"

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string broken = coulomb::fuzz::COULOMB_FUZZ_ENTRY(data, size);
  if (!broken.empty()) {
    std::fprintf(stderr, "coulomb fuzz: invariant broken: %s\n", broken.c_str());
    std::abort();
  }
  return 0;
}
