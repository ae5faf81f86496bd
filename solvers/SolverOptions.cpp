#include <coulomb/solvers/SolverOptions.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::solvers {
namespace {

// The message of a bad field; the stream exists only on this path (validation runs every solve).
template <class Value>
std::string bad(const char* field, Value value, const char* rule) {
  std::ostringstream s;
  s << field << " = " << value << ": " << rule;
  return s.str();
}

}  // namespace

std::optional<std::string> validateOptions(const SolverOptions& options) {
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance))
    return bad("tolerance", options.tolerance, "must be finite and >= 0");
  if (options.maxIterations < 0)
    return bad("maxIterations", options.maxIterations, "must be >= 0 (0 = solver default)");
  if (options.stallWindow < 0)
    return bad("stallWindow", options.stallWindow, "must be >= 0 (0 = solver default)");
  if (options.sweepPartBlocks < 0)
    return bad("sweepPartBlocks", options.sweepPartBlocks, "must be >= 0 (0 = never)");
  if (!(options.timeLimitSeconds > 0.0))
    return bad("timeLimitSeconds", options.timeLimitSeconds, "must be > 0");
  return std::nullopt;
}

}  // namespace coulomb::solvers
