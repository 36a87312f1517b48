# Writes ${OUT} with the code version (git describe) at build time; rewrites it only when it changed,
# so that only the files that record provenance recompile.
execute_process(COMMAND git describe --always --dirty --tags WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE v OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT v)
  set(v "unknown")
endif()
set(content "#pragma once\n// Generated at build time by cmake/version.cmake.\n#define DEM2D_VERSION \"${v}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL content)
  file(WRITE ${OUT} "${content}")
endif()
