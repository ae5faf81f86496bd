// Keeps the target non-empty until the first solver source lands; delete it then.
namespace coulomb::solvers {
int placeholderSymbol() { return 0; }
}  // namespace coulomb::solvers
