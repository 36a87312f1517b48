#!/usr/bin/env bash
# Packs what the 16-core benchmark (bench/scaling.py) needs into one archive for a machine that has no
# Debian packages and no network (bench/README.md, "Sixteen cores"): dem2d (Release; optionally a second
# build to compare, and the MPI build for studies over ranks), Debian's LAMMPS (`lmp`) and Open MPI
# (`orterun`, its plugins and PMIx), and every shared library they load except the C library itself.
# Open MPI is relocated with OPAL_PREFIX (its tree is kept as Debian lays it out, under usr/).
#
#   bench/portable/pack.sh [--base PATH] [--out FILE]
#     --base PATH   a second dem2d to measure beside build/app/dem2d (e.g. main before a change)
#     --out FILE    the archive (default bench/portable/bundle.tar.xz; ignored by git)
# Unpack and run there with bench/portable/run.sh (the repository travels beside it).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
BASE="" OUT="$ROOT/bench/portable/bundle.tar.xz"
while [ $# -gt 0 ]; do
  case "$1" in
    --base) BASE=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) echo "pack.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
for f in "$ROOT/build/app/dem2d" /usr/bin/lmp /usr/bin/orterun; do
  [ -x "$f" ] || { echo "pack.sh: $f missing (cmake --build build; scripts/setup.sh --bench --mpi)" >&2; exit 1; }
done
grep -q '"Release"\|Release' "$ROOT/build/CMakeCache.txt" || { echo "pack.sh: build/ is not a Release build" >&2; exit 1; }
STAGE=$(mktemp -d)
trap 'rm -rf "$STAGE"' EXIT
B=$STAGE/dem2d_bundle
mkdir -p "$B/bin" "$B/lib"
cp "$ROOT/build/app/dem2d" "$B/bin/dem2d"
[ -n "$BASE" ] && cp "$BASE" "$B/bin/dem2d_base"
[ -x "$ROOT/build-mpi/app/dem2d" ] && cp "$ROOT/build-mpi/app/dem2d" "$B/bin/dem2d_mpi"
cp /usr/bin/lmp "$B/bin/lmp"
# Open MPI and PMIx as Debian lays them out (OPAL_PREFIX=$B/usr re-bases every path under /usr)
OMPI=/usr/lib/x86_64-linux-gnu/openmpi PMIX=/usr/lib/x86_64-linux-gnu/pmix2
mkdir -p "$B/usr/bin" "$B/usr/lib/x86_64-linux-gnu" "$B/usr/share" "$B/etc"
cp /usr/bin/orterun "$B/usr/bin/orterun"
ln -s orterun "$B/usr/bin/mpirun"
cp -a "$OMPI" "$B/usr/lib/x86_64-linux-gnu/"
[ -d "$PMIX" ] && cp -a "$PMIX" "$B/usr/lib/x86_64-linux-gnu/"
cp -a /usr/share/openmpi "$B/usr/share/"
[ -d /usr/share/pmix ] && cp -a /usr/share/pmix "$B/usr/share/"
cp -a /etc/openmpi "$B/etc/"
# every shared library any of them loads, but the C library's own (the target has its own, newer)
glibc='^(libc|libm|libpthread|libdl|librt|libresolv|libutil|ld-linux-x86-64)\.so'
{
  ls "$B"/bin/*
  echo "$B/usr/bin/orterun"
  find "$B/usr/lib" -name '*.so*' -type f
} | while read -r f; do ldd "$f" 2>/dev/null | awk '$3 ~ /^\// {print $3}'; done | sort -u | while read -r lib; do
  name=$(basename "$lib")
  [[ "$name" =~ $glibc ]] && continue
  case "$lib" in "$OMPI"/*|"$PMIX"/*) continue ;; esac  # in the relocated tree already
  cp -L "$lib" "$B/lib/$name"
done
cp "$ROOT/bench/portable/env.sh" "$B/env.sh"
mkdir -p "$(dirname "$OUT")"
tar -C "$STAGE" -cf - dem2d_bundle | xz -T2 -6 > "$OUT.part"
mv "$OUT.part" "$OUT"
echo "pack.sh: $OUT ($(du -h "$OUT" | cut -f1)); unpack: tar -xJf $(basename "$OUT"); source dem2d_bundle/env.sh"
