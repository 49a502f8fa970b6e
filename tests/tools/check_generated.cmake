# Runs GENERATOR (a command list; the output path is appended) into SCRATCH_DIR and fails
# when its output differs from the COMMITTED copy. Removes what it wrote.
file(REMOVE_RECURSE "${SCRATCH_DIR}")
file(MAKE_DIRECTORY "${SCRATCH_DIR}")
get_filename_component(name "${COMMITTED}" NAME)
set(fresh "${SCRATCH_DIR}/${name}")
execute_process(COMMAND ${GENERATOR} "${fresh}" RESULT_VARIABLE code
                OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  file(REMOVE_RECURSE "${SCRATCH_DIR}")
  message(FATAL_ERROR "generator failed (${code}): ${GENERATOR}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${fresh}" "${COMMITTED}"
                RESULT_VARIABLE differ)
if(differ)
  execute_process(COMMAND diff -u "${COMMITTED}" "${fresh}" OUTPUT_VARIABLE delta)
  file(REMOVE_RECURSE "${SCRATCH_DIR}")
  string(SUBSTRING "${delta}" 0 4000 delta)
  message(FATAL_ERROR "${COMMITTED} is stale; regenerate it with the target "
                      "regenerate_<name> (tools/CMakeLists.txt):\n${delta}")
endif()
file(REMOVE_RECURSE "${SCRATCH_DIR}")
message(STATUS "${COMMITTED} is what its generator writes today")
