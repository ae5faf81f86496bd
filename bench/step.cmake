# Step cost per scene: ms per step (median, p99, max), first step, allocations per step, iterations
# and residual (docs/benchmarks.md, "The step rebuilt"). Counts allocations: not under the
# sanitizers (no coulomb_heap_counter there).
if(TARGET coulomb_samples AND TARGET coulomb_heap_counter)
  coulomb_add_executable(StepCost SOURCES StepCost.cpp LINKS coulomb_samples coulomb_heap_counter)
endif()
# Scene query cost (docs/embedding.md, "Scene queries"): ray casts, shape casts, overlaps and AABB
# queries per second against a scene, and the cost of the sync after a step.
if(TARGET coulomb_samples)
  coulomb_add_executable(QueryCost SOURCES QueryCost.cpp LINKS coulomb_samples)
endif()
# Threads (docs/embedding.md, "Threads"): ms per step at 1 and N threads, the speed-up, the
# serial fraction and Amdahl's estimate; the state hash must not change with the count.
if(TARGET coulomb_samples)
  coulomb_add_executable(ThreadScaling SOURCES ThreadScaling.cpp LINKS coulomb_samples)
endif()
