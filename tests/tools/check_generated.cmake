# Runs GENERATOR (a command list; the output path is appended) into SCRATCH_DIR and fails
# when its output says something else than the COMMITTED copy: COMPARE (compare_generated)
# with the tolerances REL and ABS on every number, the text exactly. Removes what it wrote.
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
execute_process(COMMAND "${COMPARE}" "${COMMITTED}" "${fresh}" "${REL}" "${ABS}"
                RESULT_VARIABLE differ OUTPUT_VARIABLE differences)
if(differ)
  execute_process(COMMAND diff -u "${COMMITTED}" "${fresh}" OUTPUT_VARIABLE delta)
  file(REMOVE_RECURSE "${SCRATCH_DIR}")
  string(SUBSTRING "${delta}" 0 4000 delta)
  message(FATAL_ERROR "${COMMITTED} is stale (numbers compared within relative ${REL}, absolute ${ABS}); "
                      "regenerate it with the target regenerate_<name> (tools/CMakeLists.txt):\n"
                      "${differences}\n${delta}")
endif()
file(REMOVE_RECURSE "${SCRATCH_DIR}")
message(STATUS "${COMMITTED} says what its generator writes today (relative ${REL}, absolute ${ABS})")
