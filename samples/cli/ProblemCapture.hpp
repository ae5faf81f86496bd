#pragma once
// `coulomb run --capture DIR [--capture-step N]`: writes each island's assembled contact problem
// as DIR/<scene>_step<N>_island<K>.fc3d (fc3d-text 1), so `coulomb solve` can replay it with every
// solver, and the warm start that solve began from (the last step's impulses) as the same name with
// `.start` (3 numbers per contact; `coulomb solve FILE --start FILE.start`). Frictionless contacts
// (a single unilateral row) are written as mu = 0 contacts whose two tangent unknowns are decoupled
// dummies (W_TT = I, q_T = 0): with mu = 0 the cone forces r_T = 0, so the normal impulse is the
// same. Rows of other kinds (bilateral, bounded, anisotropic friction) have no fc3d form: such
// islands are counted and skipped (docs/solvers.md).
#include <coulomb/engine/World.hpp>
#include <coulomb/solvers/ContactProblem.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace coulomb::cli {

/// The pure contact form of `problem` (unilateral rows padded as above), or nullopt if it holds
/// rows fc3d cannot express.
std::optional<solvers::ContactProblem> asPureContactProblem(const solvers::ContactProblem& problem);

class ProblemCapture {
 public:
  /// Creates `directory` if needed; throws CommandError naming it if that fails.
  ProblemCapture(std::filesystem::path directory, std::string sceneName,
                 std::optional<std::uint64_t> onlyStep);
  /// Installs the world's problem observer (it refers to this object: keep it alive).
  void attach(engine::World& world);
  /// Throws CommandError with the first write failure, if any.
  void throwIfFailed() const;
  [[nodiscard]] std::uint64_t filesWritten() const { return filesWritten_; }
  [[nodiscard]] std::uint64_t islandsSkipped() const { return islandsSkipped_; }

 private:
  void capture(std::uint64_t step, std::int32_t island, const solvers::ContactProblem& problem);

  std::filesystem::path directory_;
  std::string sceneName_;
  std::optional<std::uint64_t> onlyStep_;
  std::uint64_t filesWritten_ = 0;
  std::uint64_t islandsSkipped_ = 0;
  std::string failure_;
};

}  // namespace coulomb::cli
