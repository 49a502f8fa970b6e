# compare_generated (COMPARE) accepts rounding-level numbers and nothing else: the same claim
# with another rounding error passes; a changed verdict, word, or number beyond the tolerance,
# or a row more, fails. Runs in SCRATCH_DIR and removes it.
file(REMOVE_RECURSE "${SCRATCH_DIR}")
file(MAKE_DIRECTORY "${SCRATCH_DIR}")
set(committed "| pull-off radius | rel. err <= 1.00e-10 | rel. err 1.21e-14 | yes |\n| P error % | 0.033 / 0.033 |\n")
file(WRITE "${SCRATCH_DIR}/committed.md" "${committed}")
# Tolerances as the checks give them: validity.md's (1e-9 relative, 1e-12 absolute) and the
# discrete study's (10 %, 0.05 percentage points).
function(expect code text what)
  set(rel 1e-9)
  set(abs 1e-12)
  if(ARGC GREATER 3)
    set(rel ${ARGV3})
    set(abs ${ARGV4})
  endif()
  file(WRITE "${SCRATCH_DIR}/fresh.md" "${text}")
  execute_process(COMMAND "${COMPARE}" "${SCRATCH_DIR}/committed.md" "${SCRATCH_DIR}/fresh.md" ${rel} ${abs}
                  RESULT_VARIABLE got OUTPUT_VARIABLE out)
  if(NOT got EQUAL code)
    file(REMOVE_RECURSE "${SCRATCH_DIR}")
    message(FATAL_ERROR "compare_generated: ${what}: exit ${got}, expected ${code}\n${out}")
  endif()
endfunction()
expect(0 "${committed}" "the same text")
expect(0 "| pull-off radius | rel. err <= 1.00e-10 | rel. err 2.10e-15 | yes |\n| P error % | 0.033 / 0.033 |\n"
       "another rounding error")
expect(1 "| pull-off radius | rel. err <= 1.00e-10 | rel. err 2.10e-15 | yes |\n| P error % | 0.027 / 0.027 |\n"
       "a percentage beyond validity.md's tolerance")
expect(0 "| pull-off radius | rel. err <= 1.00e-10 | rel. err 2.10e-15 | yes |\n| P error % | 0.027 / 0.027 |\n"
       "a percentage within the discrete study's tolerance" 0.1 0.05)
expect(1 "| pull-off radius | rel. err <= 1.00e-10 | rel. err 1.21e-14 | no |\n| P error % | 0.033 / 0.033 |\n"
       "a changed verdict")
expect(1 "| pull-off radius | rel. err <= 1.00e-10 | rel. err 1.21e-14 | yes |\n| P error % | 0.33 / 0.033 |\n"
       "a number beyond the discrete study's tolerance" 0.1 0.05)
expect(1 "| pull-off radius | rel. err <= 1.00e-09 | rel. err 1.21e-14 | yes |\n| P error % | 0.033 / 0.033 |\n"
       "a changed bound")
expect(1 "${committed}| more |\n" "a row more")
file(REMOVE_RECURSE "${SCRATCH_DIR}")
