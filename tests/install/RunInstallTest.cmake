# cmake -P script: install the build tree, then build and run tests/install/app against it.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "command failed (${status}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${APP_SOURCE_DIR} -B ${WORK_DIR}/app -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/app)
# Linked with the core libraries alone: no optional component's library on its link line.
file(GLOB_RECURSE link_rules ${WORK_DIR}/app/*.ninja ${WORK_DIR}/app/*link.txt)
foreach(rules IN LISTS link_rules)
  file(READ ${rules} text)
  if(text MATCHES "assimp|qhull|urdfdom|coulomb_meshes|coulomb_urdf|coulomb_io")
    message(FATAL_ERROR "command failed: the core consumer links ${CMAKE_MATCH_0} (${rules})")
  endif()
endforeach()
run(${WORK_DIR}/app/consumer)
# The game-like embedding sample, a project of its own on the public headers and coulomb::core.
run(${CMAKE_COMMAND} -S ${SAMPLE_SOURCE_DIR} -B ${WORK_DIR}/sample -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/sample)
execute_process(COMMAND ${WORK_DIR}/sample/sample_embedding 120 RESULT_VARIABLE status
                OUTPUT_VARIABLE out)
message("${out}")
if(NOT status EQUAL 0 OR NOT out MATCHES "ray pick straight down over the lift: crate")
  message(FATAL_ERROR "command failed: the installed embedding sample (${status})")
endif()
if(PYTHON)
  set(check "import coulomb, numpy as np, sys\n\
assert coulomb.__file__.startswith(sys.argv[1]), coulomb.__file__\n\
r = coulomb.solve(coulomb.ContactProblem(np.eye(3), [-1.0, 0.5, 0.0], [0.3]), 'ac_newton', tol=1e-12)\n\
assert r.converged and abs(r.impulses[1] + 0.3) < 1e-9, r\n\
print('coulomb python ok')")
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR} PYTHONDONTWRITEBYTECODE=1
      ${PYTHON} -c "${check}" ${WORK_DIR}/prefix/${PYTHON_DIR})
endif()
