// Keeps the target non-empty until the first solver source lands; delete it then.
namespace coulomb::engine {
int placeholderSymbol() { return 0; }
}  // namespace coulomb::engine
