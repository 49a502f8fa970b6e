# Installs the build tree BUILD_DIR into a temporary prefix, configures, builds and runs
# the consumer project against it with the scene SCENE, and removes everything it wrote.
set(scratch "${SCRATCH_DIR}")
file(REMOVE_RECURSE "${scratch}")
file(MAKE_DIRECTORY "${scratch}")
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    file(REMOVE_RECURSE "${scratch}")
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
step(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${scratch}/prefix")
step(${CMAKE_COMMAND} -S "${CONSUMER_DIR}" -B "${scratch}/build" -G Ninja
     -DCMAKE_PREFIX_PATH=${scratch}/prefix -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
     -DCMAKE_BUILD_TYPE=Release)
step(${CMAKE_COMMAND} --build "${scratch}/build")
step("${scratch}/build/consumer" "${SCENE}")
file(REMOVE_RECURSE "${scratch}")
