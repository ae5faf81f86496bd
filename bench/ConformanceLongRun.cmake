# The conformance cases at their full docs/scene-specifications.md horizons (issue 8 item 5: 10 000 steps of the
# towers, pyramids and the 1000-box pile), too long for CI: `ConformanceLongRun [--solvers a,b]
# [--scale X] CASE...` prints one line per case and solver (docs/conformance.md has the figures).
if(TARGET coulomb_samples)
  coulomb_add_executable(ConformanceLongRun SOURCES ConformanceLongRun.cpp LINKS coulomb_samples)
endif()
