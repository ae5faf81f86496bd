// Keeps the target non-empty until the first solver source lands; delete it then.
namespace coulomb::joints {
int placeholderSymbol() { return 0; }
}  // namespace coulomb::joints
