# Fails unless DOC contains the text of PART verbatim: a table copied into a page from the
# committed file a generator writes (docs/data) must be that file's today.
file(READ "${DOC}" doc)
file(READ "${PART}" part)
string(FIND "${doc}" "${part}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${DOC} does not contain ${PART} as it is: copy the table again")
endif()
