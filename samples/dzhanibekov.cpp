// Sample: runs the built-in 'dzhanibekov' scene and prints what it measures (see
// FreeFlightSamples.hpp).
#include <coulomb/engine/CoulombError.hpp>

#include <iostream>

#include "FreeFlightSamples.hpp"
#include "scenes/SceneRegistry.hpp"

int main() {
  try {
    coulomb::samples::print(std::cout, coulomb::samples::measureDzhanibekov(
                                           coulomb::scenes::loadBuiltinScene("dzhanibekov")));
  } catch (const std::exception& e) {
    std::cerr << "dzhanibekov: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
