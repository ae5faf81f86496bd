// Sample: runs the built-in 'symmetric_top' scene and prints what it measures (see
// FreeFlightSamples.hpp).
#include <coulomb/engine/CoulombError.hpp>

#include <iostream>

#include "FreeFlightSamples.hpp"
#include "scenes/SceneRegistry.hpp"

int main() {
  try {
    coulomb::samples::print(std::cout, coulomb::samples::measureSymmetricTop(
                                           coulomb::scenes::loadBuiltinScene("symmetric_top")));
  } catch (const std::exception& e) {
    std::cerr << "symmetric_top: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
