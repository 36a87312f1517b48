# cmake -DDEM2D=<dem2d> -DCASE=<case.toml> -P check_located_error.cmake
# Passes if `dem2d check CASE` exits with status 2 (a refused case; a signal is not a number) and its
# stderr is one `error: CASE:<line>: …` message.
execute_process(COMMAND ${DEM2D} check ${CASE} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "^error: [^\n]*:[0-9]+: [^\n]+\n$" located "${err}")
if(NOT rc STREQUAL "2" OR NOT located)
  message(FATAL_ERROR "dem2d check ${CASE}: expected exit status 2 and 'error: file:line: ...', "
                      "got status '${rc}', stdout '${out}', stderr '${err}'")
endif()
string(FIND "${err}" "${CASE}:" at)
if(NOT at EQUAL 7)
  message(FATAL_ERROR "dem2d check ${CASE}: the error does not name the case file: ${err}")
endif()
message(STATUS "dem2d check refused ${CASE} (status 2): ${err}")
