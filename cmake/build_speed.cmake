# Compile time (issue 54, docs/toolchain.md "Build time"): what makes the builds of CI and a newcomer's first
# build shorter, without changing what any build computes.
#
# ccache (Debian ccache, scripts/setup.sh), when installed: CCACHE_BASEDIR makes the cache keys relative to
# the source tree, so that a second build tree with the same flags (build-mpi/ beside build/) or a later
# clone reuses the objects; pch_defines,time_macros lets it cache the files compiled with a precompiled
# header. -DDEM2D_CCACHE=OFF, or a launcher of one's own (CMAKE_CXX_COMPILER_LAUNCHER), leaves it out.
option(DEM2D_CCACHE "Compile through ccache when it is installed" ON)
if(DEM2D_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(DEM2D_CCACHE_PROGRAM ccache)
  if(DEM2D_CCACHE_PROGRAM)
    set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${CMAKE_SOURCE_DIR} CCACHE_NOHASHDIR=1
        CCACHE_SLOPPINESS=pch_defines,time_macros ${DEM2D_CCACHE_PROGRAM})
    message(STATUS "dem2d: compiling through ${DEM2D_CCACHE_PROGRAM}")
  endif()
endif()

# Precompiled headers, with clang only (the sanitizer builds: scripts/sanitize.sh, scripts/tsan.sh): the
# third-party headers every file of a target reads (Catch2's single header, nlohmann/json, fmt,
# <filesystem>) are parsed once per target instead of once per file. Measured on four test files (user +
# system seconds, docs/toolchain.md "Build time"): clang ASan + UBSan 45.7 s without, 33.1 s with; g++ -O3
# 34.2 s without, 33.6 s with (a 120 MB .gch loaded per file costs about what it saves), so not with g++.
# -DDEM2D_PCH=OFF compiles without.
option(DEM2D_PCH "Precompile the third-party headers of the test executables and the study engine (clang)" ON)
function(dem2d_precompile target)
  if(DEM2D_PCH AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
set(DEM2D_PCH_COMMON <cmath> <filesystem> <string> <vector> <nlohmann/json.hpp> <fmt/format.h>)

# The test executables' own code is compiled with less optimisation than the library it tests: -O1 in the
# Release build (-O3 for the library; the test files took 20 % less time: 34.2 s → 27.5 s on the four),
# -O0 in the sanitizer builds (-O1 for the library: 45.7 s → 32.4 s). Nothing a test checks depends on it:
# the results of the library's code are its own, and without -ffast-math (and with -std=c++20, no FMA
# contraction) the optimisation level does not change a floating-point result.
function(dem2d_test_optimisation target)
  if(DEM2D_SANITIZE OR CMAKE_CXX_FLAGS MATCHES "-fsanitize=thread")
    target_compile_options(${target} PRIVATE -O0)
    # The test files need no libFuzzer coverage (only the fuzz/ targets are fuzzed; the library they link
    # keeps it): 17–21 % less compile time per test file (docs/toolchain.md "Build time"). ASan and UBSan
    # stay on.
    if(DEM2D_FUZZ)
      target_compile_options(${target} PRIVATE -fno-sanitize=fuzzer-no-link)
    endif()
  else()
    target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-O1>)
  endif()
endfunction()
