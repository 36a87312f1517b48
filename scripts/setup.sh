#!/usr/bin/env bash
# Installs the Debian packages the testbed needs (only those missing). Safe to run repeatedly.
# Package list and CMake targets: docs/toolchain.md.
set -euo pipefail
pkgs=(build-essential cmake libeigen3-dev libgsl-dev catch2 libboost-dev libtomlplusplus-dev
      libcli11-dev nlohmann-json3-dev libfmt-dev gnuplot-nox
      # PNG force-network pictures (zlib) and the check of the ParaView snapshots with VTK's reader
      # (ctest -L tools, tests/tools/check_vtk_snapshots.py)
      zlib1g-dev python3-vtk9
      # the browser check of the report (ctest -L browser, tests/browser/check_report.py)
      chromium python3
      # sanitizers and fuzzing (scripts/sanitize.sh, scripts/fuzz.sh): clang 14, its runtime libraries
      # (ASan, UBSan, libFuzzer: libclang_rt.fuzzer-x86_64.a, only a Recommends of clang) and
      # llvm-symbolizer (package llvm) for readable stack traces
      clang libclang-rt-dev llvm)
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
