# Maximal-coordinate joints (docs/tuning.md "Joints" has the figures): ms per step, max joint gap
# and energy drift of the docs/scene-specifications.md A6 chain with 10, 50 and 200 links, per solver (pgs, bgs,
# ac_newton) and per stabilization policy (predicted_state, baumgarte), at dt 0.01 and 0.002.
coulomb_add_bench(JointChainBench.cpp LINKS coulomb::io coulomb_samples)
