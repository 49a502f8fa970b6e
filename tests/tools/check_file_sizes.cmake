# Fails when a source file under SOURCE_DIR/src holds more than MAX_LINES lines: one concept
# per file keeps them small (docs/development.md).
file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/src/*.cpp" "${SOURCE_DIR}/src/*.hpp")
set(too_long "")
foreach(f IN LISTS sources)
  file(STRINGS "${SOURCE_DIR}/${f}" lines)
  list(LENGTH lines n)
  if(n GREATER MAX_LINES)
    string(APPEND too_long "\n  ${f}: ${n} lines")
  endif()
endforeach()
if(too_long)
  message(FATAL_ERROR "files over ${MAX_LINES} lines (split them by concept):${too_long}")
endif()
