#!/usr/bin/env bash
# compare_builds.sh: builds ntn-run-<model> (tests/determinism/runner) with every compiler and
# flag set it can — g++ and clang++, at -O0, -O2, -O3, each without and with -march=native —
# each in its own directory under WORK, runs it on RECORD and compares the printed output hash
# and the CSV byte for byte with the reference runner of the main build: once by the SIMD element
# pass (each build's widest vectors) and once by the scalar reference (--element-pass scalar).
#   compare_builds.sh SOURCE_DIR MODEL_DIR MODEL_NAME REFERENCE_RUNNER RECORD WORK
# A compiler that is not installed is reported and left out (at least one must be there).
set -euo pipefail
src=$1 model_dir=$2 model=$3 ref=$4 record=$5 work=$6
mkdir -p "$work"
trap 'rm -f "$work"/*.csv' EXIT

run() { # run BINARY CSV [OPTION...] -> prints the "output hash ..." line
  local bin=$1 csv=$2
  shift 2
  "$bin" -q --input "ag_x=$record" --out "$csv" "$@" | grep 'output hash'
}

ref_hash=$(run "$ref" "$work/reference.csv")
echo "reference ($ref): $ref_hash"
fail=0 built=0
for cxx in g++ clang++; do
  if ! command -v "$cxx" >/dev/null; then
    echo "SKIPPED $cxx: not installed"
    continue
  fi
  for opt in -O0 -O2 -O3; do
    for arch in "" "-march=native"; do
      name="${cxx}${opt}${arch:+-native}"
      dir="$work/$name"
      start=$(date +%s)
      cmake -S "$src/tests/determinism/runner" -B "$dir" -DCMAKE_BUILD_TYPE=None \
        -DCMAKE_CXX_COMPILER="$cxx" "-DCMAKE_CXX_FLAGS=$opt $arch" -DNTN_SOURCE_DIR="$src" \
        -DNTN_MODEL_DIR="$model_dir" -DNTN_MODEL_NAME="$model" >"$dir.log" 2>&1
      cmake --build "$dir" -j2 >>"$dir.log" 2>&1 || {
        echo "FAIL $name: build failed (see $dir.log)"
        fail=1
        continue
      }
      built=$((built + 1))
      for pass in simd scalar; do
        hash=$(run "$dir/ntn-run-$model" "$work/$name.csv" --element-pass "$pass")
        if [ "$hash" = "$ref_hash" ] && cmp -s "$work/reference.csv" "$work/$name.csv"; then
          echo "same  $name ($pass):$hash ($(($(date +%s) - start)) s)"
        else
          echo "DIFF  $name ($pass):$hash (reference$ref_hash)"
          cmp "$work/reference.csv" "$work/$name.csv" | head -1 || true
          fail=1
        fi
      done
    done
  done
done
[ "$built" -gt 0 ] || { echo "FAIL: no variant could be built"; exit 1; }
echo "$built variants built; $([ $fail = 0 ] && echo 'all bit-identical' || echo 'DIFFERENCES')"
exit $fail
