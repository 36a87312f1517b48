# The Python module (python/README.md): on by default when pybind11 is found (Debian pybind11-dev and
# python3-pybind11, scripts/setup.sh), off otherwise; the rest of the build does not need it. Built against
# the system interpreter (/usr/bin/python3: Debian's python3-pandas, -pytest, -scipy live there, not in a
# pyenv or venv python3 on PATH). The module links the static libraries of the core, the study engine and the
# report, so these are compiled as position-independent code when it is on (the same objects for the
# command line and the module: their results are the same bit for bit).
find_program(DEM2D_SYSTEM_PYTHON3 NAMES python3 PATHS /usr/bin /bin NO_DEFAULT_PATH)
set(_dem2d_python_default OFF)
if(DEM2D_SYSTEM_PYTHON3 AND NOT DEM2D_SANITIZE AND NOT DEM2D_FUZZ)
  set(Python_EXECUTABLE ${DEM2D_SYSTEM_PYTHON3} CACHE FILEPATH "The Python the module is built for")
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  if(pybind11_FOUND)
    set(_dem2d_python_default ON)
  endif()
endif()
option(DEM2D_PYTHON "Build the Python module (python/, import dem2d from build/python)" ${_dem2d_python_default})
if(DEM2D_PYTHON)
  if(NOT pybind11_FOUND)
    find_package(pybind11 CONFIG REQUIRED)
  endif()
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  # -fPIC would let a call to a global function of the same file be interposed, which stops g++ from
  # inlining it: keep the non-PIC code's inlining (the library is never interposed)
  add_compile_options($<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
  message(STATUS "dem2d: Python module on (pybind11 ${pybind11_VERSION}, ${Python_EXECUTABLE})")
else()
  message(STATUS "dem2d: Python module off (pybind11 not found, or DEM2D_PYTHON=OFF)")
endif()
