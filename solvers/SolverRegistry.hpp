#pragma once
// The solvers known by name: an explicit table filled by builtInSolvers() (no static
// initialisers, no singletons). Callers may add their own entries to a registry they own.
#include <coulomb/solvers/ContactSolver.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace coulomb::solvers {

struct SolverEntry {
  std::string name;                                        // e.g. "ac_newton": the --solver value
  std::string summary;                                     // one line for `coulomb solvers`
  std::function<std::unique_ptr<ContactSolver>()> create;  // with default options
};

class SolverRegistry {
 public:
  // pgs, bgs, ac_newton (and the later families, one line each in SolverRegistry.cpp).
  static SolverRegistry builtIn();

  void add(SolverEntry entry);  // throws std::invalid_argument on a duplicate or empty name
  [[nodiscard]] const std::vector<SolverEntry>& entries() const { return entries_; }
  [[nodiscard]] const SolverEntry* find(const std::string& name) const;
  [[nodiscard]] std::unique_ptr<ContactSolver> create(const std::string& name) const;  // or null
  [[nodiscard]] std::vector<std::string> names() const;

 private:
  std::vector<SolverEntry> entries_;
};

}  // namespace coulomb::solvers
