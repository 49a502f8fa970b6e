# Fails unless README.md contains, verbatim, the command .ci/run executes: CI must run
# exactly the README's test command.
file(STRINGS "${CI_RUN}" ci_lines)
list(GET ci_lines -1 command)
file(READ "${README}" readme)
string(FIND "${readme}" "${command}" position)
if(position EQUAL -1)
  message(FATAL_ERROR "README.md does not contain the CI command:\n  ${command}")
endif()
message(STATUS "README.md contains the CI command: ${command}")
