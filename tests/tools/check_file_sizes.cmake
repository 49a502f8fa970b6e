# Fails when a source file under SOURCE_DIR (src/, include/, python/: C++ and Python) holds more
# than MAX_LINES non-blank lines: one concept per file keeps them small (docs/development.md).
# The count does not use file(STRINGS) and list(LENGTH) on the text as it is: a CMake list splits
# at every ';' (a C++ file would count its statements), an unbalanced '[' hides the separators
# after it and a '\' escapes the next. Those characters become 'x' first (a line of "]" alone stays
# a line), then the non-blank lines are matched one by one.
file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}"
     "${SOURCE_DIR}/src/*.cpp" "${SOURCE_DIR}/src/*.hpp" "${SOURCE_DIR}/include/*.hpp"
     "${SOURCE_DIR}/python/*.py" "${SOURCE_DIR}/python/*.cpp" "${SOURCE_DIR}/python/*.hpp")
set(too_long "")
set(counted 0)
foreach(f IN LISTS sources)
  file(READ "${SOURCE_DIR}/${f}" content)
  string(REGEX REPLACE "[][;\\]" "x" content "${content}")
  string(REGEX MATCHALL "[^\n]*[^ \t\r\n][^\n]*" nonblank "${content}")
  list(LENGTH nonblank n)
  math(EXPR counted "${counted} + 1")
  if(n GREATER MAX_LINES)
    string(APPEND too_long "\n  ${f}: ${n} non-blank lines")
  endif()
endforeach()
if(too_long)
  message(FATAL_ERROR "files over ${MAX_LINES} non-blank lines (split them by concept):${too_long}")
endif()
message(STATUS "${counted} files, none over ${MAX_LINES} non-blank lines")
