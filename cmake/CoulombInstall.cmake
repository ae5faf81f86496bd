# The installed package: one export set per component, so that find_package(coulomb CONFIG
# COMPONENTS core) looks for Eigen, FCL and libccd only (cmake/coulombConfig.cmake.in).
include(CMakePackageConfigHelpers)
foreach(component Core Meshes Urdf Io)
  install(EXPORT coulomb${component}Targets NAMESPACE coulomb:: DESTINATION lib/cmake/coulomb)
endforeach()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/coulombConfig.cmake.in
  ${PROJECT_BINARY_DIR}/coulombConfig.cmake INSTALL_DESTINATION lib/cmake/coulomb)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/coulombConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/coulombConfig.cmake ${PROJECT_BINARY_DIR}/coulombConfigVersion.cmake
        DESTINATION lib/cmake/coulomb)
