# The contact-solver corpus runner (docs/solvers.md): SolverCorpusBench FOLDER [options].
# It compares against the reference residual of tests/data/fc3d/fc3d_text.hpp (a copy of the
# corpus header). Not a Google Benchmark program: it prints the Markdown table of the docs.
coulomb_add_executable(SolverCorpusBench SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/SolverCorpusBench.cpp
                       LINKS coulomb::solvers coulomb_samples)
target_include_directories(SolverCorpusBench PRIVATE ${PROJECT_SOURCE_DIR}/tests/data/fc3d)
