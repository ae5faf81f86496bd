# Collision pipeline speed: broad + narrow phase per step (docs/collision.md has the figures).
coulomb_add_bench(CollisionBench.cpp LINKS coulomb::geometry)
