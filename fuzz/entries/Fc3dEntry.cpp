#include "entries/FuzzEntries.hpp"
#include "entries/SolveAll.hpp"

#include <coulomb/solvers/io/Fc3dText.hpp>

#include <exception>
#include <sstream>

namespace coulomb::fuzz {

std::string fc3dEntry(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const solvers::Fc3dReadResult read = solvers::parseFc3dText(in, "fuzz.fc3d");
    if (read.problem.has_value() == !read.error.empty())
      return "parseFc3dText gave " +
             std::string(read.problem ? "a problem and" : "neither a problem nor") +
             " an error: '" + read.error + "'";
    // Small problems only: each input must run in milliseconds.
    if (read.problem && read.problem->size() <= 24) return solveWithEverySolver(*read.problem, 20);
  } catch (const std::exception& e) {
    return std::string("parseFc3dText threw instead of returning an error: ") + e.what();
  }
  return {};
}

}  // namespace coulomb::fuzz
