# Collision pipeline speed: broad + narrow phase per step (docs/collision.md has the figures).
coulomb_add_bench(CollisionBench.cpp LINKS coulomb::geometry)
# Per-pair narrow-phase cost of the feature manifolds against FCL's collide alone.
coulomb_add_bench(PairContactBench.cpp LINKS coulomb_samples)
