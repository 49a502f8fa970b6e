# Runs COMMAND (a list) with its standard output written to OUTPUT; fails if it fails.
execute_process(COMMAND ${COMMAND} OUTPUT_FILE "${OUTPUT}" RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "failed (${code}): ${COMMAND}")
endif()
