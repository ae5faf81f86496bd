# coulomb_add_library(<folder> [EXPORT_SET <set>] [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
#
# Builds coulomb_<folder> (alias coulomb::<folder>) from every .cpp under <folder>/, installed in
# the export set of its component (default coulombCoreTargets; cmake/CoulombInstall.cmake).
# Its headers are installed under include/coulomb/detail/ (internals: the public headers are
# include/coulomb/*.hpp).
# Headers live beside sources and are included as <coulomb/<folder>/X.hpp>: each target gets its
# own include root holding a single link coulomb/<folder> -> <source>/<folder>, so a header of a
# folder that is not linked is simply not found (the dependency graph is enforced by the build).
set(COULOMB_WARNINGS -Wall -Wextra -Wpedantic -Werror)

function(coulomb_add_library folder)
  cmake_parse_arguments(ARG "" "EXPORT_SET" "PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  if(NOT ARG_EXPORT_SET)
    set(ARG_EXPORT_SET coulombCoreTargets)
  endif()
  set(target coulomb_${folder})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${folder}/*.cpp)
  add_library(${target} STATIC ${sources})
  add_library(coulomb::${folder} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${folder} OUTPUT_NAME coulomb_${folder}
                                             POSITION_INDEPENDENT_CODE ON)
  set(include_root ${PROJECT_BINARY_DIR}/include_roots/${folder})
  file(MAKE_DIRECTORY ${include_root}/coulomb)
  if(NOT EXISTS ${include_root}/coulomb/${folder})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${include_root}/coulomb/${folder} SYMBOLIC)
  endif()
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${include_root}>
                                              $<INSTALL_INTERFACE:include/coulomb/detail>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE ${COULOMB_WARNINGS})
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION include/coulomb/detail/coulomb/${folder}
          FILES_MATCHING PATTERN "*.hpp")
  install(TARGETS ${target} EXPORT ${ARG_EXPORT_SET} ARCHIVE DESTINATION lib LIBRARY DESTINATION lib)
endfunction()

# coulomb_add_executable(<name> <sources...> LINKS ...): a program in build/bin.
function(coulomb_add_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINKS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_options(${name} PRIVATE ${COULOMB_WARNINGS})
  target_link_libraries(${name} PRIVATE ${ARG_LINKS})
endfunction()
