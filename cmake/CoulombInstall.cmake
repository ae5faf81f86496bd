include(CMakePackageConfigHelpers)
install(EXPORT coulombTargets NAMESPACE coulomb:: DESTINATION lib/cmake/coulomb)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/coulombConfig.cmake.in
  ${PROJECT_BINARY_DIR}/coulombConfig.cmake INSTALL_DESTINATION lib/cmake/coulomb)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/coulombConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/coulombConfig.cmake ${PROJECT_BINARY_DIR}/coulombConfigVersion.cmake
        DESTINATION lib/cmake/coulomb)
