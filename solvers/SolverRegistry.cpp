#include <coulomb/solvers/SolverRegistry.hpp>

#include <coulomb/solvers/bgs/BgsSolver.hpp>
#include <coulomb/solvers/direct/EqualityLdltSolver.hpp>
#include <coulomb/solvers/lemke/LemkeSolver.hpp>
#include <coulomb/solvers/newton/AcNewtonSolver.hpp>
#include <coulomb/solvers/newton/FbNewtonSolver.hpp>
#include <coulomb/solvers/pgs/PgsSolver.hpp>
#include <coulomb/solvers/staggered/StaggeredSolver.hpp>

#include <stdexcept>

namespace coulomb::solvers {
namespace {

// A factory of `Solver` with its default options changed by `set` (variants under their own
// registry names: nncg, bgs_nncg, prox).
template <class Solver, class Options, class Set>
std::function<std::unique_ptr<ContactSolver>()> variant(Set set) {
  return [set] {
    Options options;
    set(options);
    return std::make_unique<Solver>(options);
  };
}

}  // namespace

SolverRegistry SolverRegistry::builtIn() {
  SolverRegistry r;
  r.add({"pgs",
         "projected Gauss-Seidel / PSOR, exact per-contact cone projection "
         "(docs/solver-derivations.md 3)",
         [] { return std::make_unique<PgsSolver>(); }});
  r.add({"bgs",
         "blocked Gauss-Seidel, exact local 3x3 contact solve (docs/solver-derivations.md 4)",
         [] { return std::make_unique<BgsSolver>(); }});
  r.add({"nncg",
         "pgs sweeps with nonsmooth nonlinear conjugate-gradient momentum (Silcowski, Erleben et "
         "al. 2015): piles, stacks and large islands once warm-started",
         variant<PgsSolver, PgsOptions>([](PgsOptions& o) { o.conjugateGradient = true; })});
  r.add({"bgs_nncg", "bgs sweeps with the same momentum: piles and stacks from a cold start",
         variant<BgsSolver, BgsOptions>([](BgsOptions& o) { o.conjugateGradient = true; })});
  r.add({"ac_newton",
         "Alart-Curnier nonsmooth Newton, Goldstein-Price search with a watchdog, regularized "
         "sparse LU "
         "(docs/solver-derivations.md 5)",
         [] { return std::make_unique<AcNewtonSolver>(); }});
  r.add({"prox",
         "proximal-point outer loop around the Alart-Curnier Newton: FC(W + s I, q - s r_k), "
         "for singular W of redundant contacts (docs/solver-derivations.md 5.9)",
         variant<AcNewtonSolver, AcNewtonOptions>(
             [](AcNewtonOptions& o) { o.proximalFromStart = true; })});
  r.add({"fb_newton",
         "Fischer-Burmeister nonsmooth Newton for second-order cones, cancellation-free "
         "eigenvalue, Armijo search, shared Newton loop (docs/solver-derivations.md 6)",
         [] { return std::make_unique<FbNewtonSolver>(); }});
  r.add({"ldlt",
         "equality rows only (joint islands without limits or contacts): W r = -q by sparse "
         "LDL^T, linear time on trees (Baraff 1996); not applicable otherwise",
         [] { return std::make_unique<EqualityLdltSolver>(); }});
  r.add({"lemke",
         "Lemke pivoting on the faceted-cone LCP (8 directions, Stewart-Trinkle slack rows), "
         "lexicographic anti-cycling (docs/solver-derivations.md 7)",
         [] { return std::make_unique<LemkeSolver>(); }});
  r.add({"staggered",
         "staggered projections (Kaufman et al. 2008): normal and friction QPs by APGD with "
         "restart (docs/solver-derivations.md 8)",
         [] { return std::make_unique<StaggeredSolver>(); }});
  return r;
}

void SolverRegistry::add(SolverEntry entry) {
  if (entry.name.empty() || !entry.create)
    throw std::invalid_argument("solver entry needs a name and a factory");
  if (find(entry.name))
    throw std::invalid_argument("solver '" + entry.name + "' already registered");
  entries_.push_back(std::move(entry));
}

const SolverEntry* SolverRegistry::find(const std::string& name) const {
  for (const SolverEntry& e : entries_)
    if (e.name == name) return &e;
  return nullptr;
}

std::unique_ptr<ContactSolver> SolverRegistry::create(const std::string& name) const {
  const SolverEntry* e = find(name);
  return e ? e->create() : nullptr;
}

std::vector<std::string> SolverRegistry::names() const {
  std::vector<std::string> n;
  for (const SolverEntry& e : entries_) n.push_back(e.name);
  return n;
}

}  // namespace coulomb::solvers
