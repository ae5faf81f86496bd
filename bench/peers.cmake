# The peer comparison in bench/peers (Bullet and ODE from Debian): off by default.
option(COULOMB_BUILD_PEERS "Build bench/peers/PeerComparison (needs libbullet-dev, libode-dev)" OFF)
if(COULOMB_BUILD_PEERS)
  if(NOT TARGET coulomb_samples)
    message(FATAL_ERROR "COULOMB_BUILD_PEERS needs COULOMB_BUILD_SAMPLES (the built-in scenes)")
  endif()
  add_subdirectory(peers)
endif()
