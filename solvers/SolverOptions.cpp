#include <coulomb/solvers/SolverOptions.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::solvers {

std::optional<std::string> validateOptions(const SolverOptions& options) {
  std::ostringstream s;
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance)) {
    s << "tolerance = " << options.tolerance << ": must be finite and >= 0";
    return s.str();
  }
  if (options.maxIterations < 0) {
    s << "maxIterations = " << options.maxIterations << ": must be >= 0 (0 = solver default)";
    return s.str();
  }
  if (options.stallWindow < 0) {
    s << "stallWindow = " << options.stallWindow << ": must be >= 0 (0 = solver default)";
    return s.str();
  }
  if (!(options.timeLimitSeconds > 0.0)) {
    s << "timeLimitSeconds = " << options.timeLimitSeconds << ": must be > 0";
    return s.str();
  }
  return std::nullopt;
}

}  // namespace coulomb::solvers
