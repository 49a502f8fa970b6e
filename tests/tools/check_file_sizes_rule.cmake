# The size rule measures: a file of 401 non-blank lines, each with semicolons (and blank lines, an
# unbalanced bracket, a backslash and a lone ']' among them), fails check_file_sizes.cmake at
# MAX_LINES 400; the same file with 400 passes.
# Writes only into SCRATCH_DIR and removes it.
file(REMOVE_RECURSE "${SCRATCH_DIR}")
function(write_file lines)
  # Every line has semicolons; line 7 is followed by blank lines and by lines that would fool a
  # list-based count: an unbalanced '[' with a ';' after it, a '\' before a ';', a ']' alone.
  set(text "")
  foreach(i RANGE 1 ${lines})
    string(APPEND text "int f${i}() { int a = 1; int b[2] = {a, a}; return b[0]; }\n")
    if(i EQUAL 7)
      string(APPEND text "\n   \n")
    endif()
  endforeach()
  string(APPEND text "const char* s = \"[\"; int c = 0; // \\\n")
  string(APPEND text "int d[] = {1, 2,\n]\n")
  file(WRITE "${SCRATCH_DIR}/src/big.cpp" "${text}")
endfunction()
foreach(case 397 398)  # plus the three trailing lines: 400 and 401
  write_file(${case})
  execute_process(COMMAND "${CMAKE_COMMAND}" -DSOURCE_DIR=${SCRATCH_DIR} -DMAX_LINES=400 -P "${CHECK}"
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  math(EXPR total "${case} + 3")
  if(case EQUAL 397 AND NOT code EQUAL 0)
    file(REMOVE_RECURSE "${SCRATCH_DIR}")
    message(FATAL_ERROR "a file of ${total} non-blank lines failed the rule at 400:\n${err}")
  endif()
  if(case EQUAL 398 AND code EQUAL 0)
    file(REMOVE_RECURSE "${SCRATCH_DIR}")
    message(FATAL_ERROR "a file of ${total} non-blank lines with semicolons passed the rule at 400:\n${out}${err}")
  endif()
  if(case EQUAL 398 AND NOT err MATCHES "src/big.cpp: 401 non-blank lines")
    file(REMOVE_RECURSE "${SCRATCH_DIR}")
    message(FATAL_ERROR "the rule counted another number of lines than 401:\n${err}")
  endif()
endforeach()
file(REMOVE_RECURSE "${SCRATCH_DIR}")
message(STATUS "the size rule fails a 401-line file with semicolons and passes a 400-line one")
