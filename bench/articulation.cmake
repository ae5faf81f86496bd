# Articulations (docs/articulations.md has the figures): ABA per step on serial chains of 10, 100
# and 1000 links (O(n)) and on URDF robots from tests/data/urdf, CRBA + Cholesky for contrast,
# and Delassus assembly for a tree with 10 contact points.
coulomb_add_bench(ArticulationBench.cpp LINKS coulomb::joints coulomb::integrators coulomb_samples
                  nlohmann_json::nlohmann_json)
target_compile_definitions(ArticulationBench PRIVATE
                           COULOMB_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
# Articulations in the World: contact assembly of a tree with 10 contacts, ms/step of the arm scene.
coulomb_add_bench(ArticulationContactBench.cpp LINKS coulomb::io)
target_compile_definitions(ArticulationContactBench PRIVATE
                           COULOMB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
# Tree integrators: ms/step and energy error of the released 10- and 50-link chains (10 s).
coulomb_add_bench(TreeIntegratorBench.cpp LINKS coulomb_samples)
