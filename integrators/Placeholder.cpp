// Keeps the target non-empty until the first solver source lands; delete it then.
namespace coulomb::integrators {
int placeholderSymbol() { return 0; }
}  // namespace coulomb::integrators
