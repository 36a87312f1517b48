#!/usr/bin/env bash
# Installs the Debian packages the testbed needs (only those missing). Safe to run repeatedly.
# Package list and CMake targets: docs/toolchain.md.
set -euo pipefail
# --mpi: also Open MPI (mpirun, the MPI C++ headers), for -DDEM2D_MPI=ON (docs/cluster.md); or DEM2D_SETUP_MPI=1.
# --bench: also what the speed benchmark needs (bench/README.md): Debian's LAMMPS (`lmp`), GNU time
# (/usr/bin/time: peak memory) and perf (where the cycles go); or DEM2D_SETUP_BENCH=1.
mpi="${DEM2D_SETUP_MPI:-0}"
bench="${DEM2D_SETUP_BENCH:-0}"
for arg in "$@"; do
  case "$arg" in
    --mpi) mpi=1 ;;
    --bench) bench=1 ;;
    *) echo "setup: unknown option $arg (known: --mpi, --bench)" >&2; exit 2 ;;
  esac
done
pkgs=(build-essential cmake
      # compiler cache: a second build tree and a rebuild reuse the objects (cmake/build_speed.cmake)
      ccache
      libeigen3-dev libgsl-dev catch2 libboost-dev libtomlplusplus-dev
      libcli11-dev nlohmann-json3-dev libfmt-dev gnuplot-nox
      # Markdown (READMEs, docs/) rendered on the report's page: cmark-gfm with GitHub's tables (reports/cited_docs.cpp)
      libcmark-gfm-dev libcmark-gfm-extensions-dev
      # PNG force-network pictures (zlib) and the check of the ParaView snapshots with VTK's reader
      # (ctest -L tools, tests/tools/check_vtk_snapshots.py)
      zlib1g-dev python3-vtk9
      # the browser check of the report (ctest -L browser, tests/browser/check_report.py)
      chromium python3
      # the test that reads a run's series.csv with pandas.read_csv defaults (tests/outputs/read_series_pandas.py)
      python3-pandas
      # the Python module (python/README.md: pybind11, the system interpreter's headers) and its tests (pytest,
      # jsonschema: the case schema of `dem2d schema`; scipy: python/examples/calibrate_friction.py)
      pybind11-dev python3-pybind11 python3-dev python3-pytest python3-scipy python3-jsonschema
      # sanitizers and fuzzing (scripts/sanitize.sh, scripts/fuzz.sh): clang 14, its runtime libraries
      # (ASan, UBSan, libFuzzer: libclang_rt.fuzzer-x86_64.a, only a Recommends of clang) and
      # llvm-symbolizer (package llvm) for readable stack traces
      clang libclang-rt-dev llvm)
[ "$mpi" = 1 ] && pkgs+=(openmpi-bin libopenmpi-dev)
[ "$bench" = 1 ] && pkgs+=(lammps time linux-perf)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
