# Step cost per scene: ms per step (median, p99, max), first step, allocations per step, iterations
# and residual (docs/benchmarks.md, "The step rebuilt").
if(TARGET coulomb_samples)
  coulomb_add_executable(StepCost SOURCES StepCost.cpp LINKS coulomb_samples)
endif()
