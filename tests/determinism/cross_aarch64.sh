#!/usr/bin/env bash
# cross_aarch64.sh: cross-builds ntn-run-<model> (tests/determinism/runner) for aarch64 with
# tools/cmake/aarch64-linux-gnu.cmake, runs it under qemu-aarch64 on RECORD and compares the
# output hash and the CSV byte for byte with the x86-64 reference runner of the main build.
#   cross_aarch64.sh SOURCE_DIR MODEL_DIR MODEL_NAME REFERENCE_RUNNER RECORD WORK
# Exits 77 (CTest SKIP_RETURN_CODE) when the cross compiler or qemu-aarch64 is not installed.
set -euo pipefail
src=$1 model_dir=$2 model=$3 ref=$4 record=$5 work=$6
for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool not installed (apt-get install g++-aarch64-linux-gnu qemu-user)"
    exit 77
  fi
done
mkdir -p "$work"
trap 'rm -f "$work"/*.csv' EXIT
run() { "$@" -q --input "ag_x=$record" --out "$csv" | grep 'output hash'; }

csv=$work/x86-64.csv
ref_hash=$(run "$ref")
dir=$work/aarch64
cmake -S "$src/tests/determinism/runner" -B "$dir" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE="$src/tools/cmake/aarch64-linux-gnu.cmake" -DNTN_SOURCE_DIR="$src" \
  -DNTN_MODEL_DIR="$model_dir" -DNTN_MODEL_NAME="$model" -DNTN_SIMD=STATIC >"$dir.log" 2>&1
cmake --build "$dir" -j2 >>"$dir.log" 2>&1 || { echo "FAIL: cross build (see $dir.log)"; exit 1; }
file "$dir/ntn-run-$model" 2>/dev/null || true
csv=$work/aarch64.csv
hash=$(run qemu-aarch64 -L /usr/aarch64-linux-gnu "$dir/ntn-run-$model")
echo "x86-64:  $ref_hash"
echo "aarch64: $hash"
if [ "$hash" = "$ref_hash" ] && cmp -s "$work/x86-64.csv" "$work/aarch64.csv"; then
  echo "aarch64 (qemu) and x86-64 outputs are bit-identical"
else
  cmp "$work/x86-64.csv" "$work/aarch64.csv" | head -1 || true
  echo "FAIL: aarch64 and x86-64 outputs differ"
  exit 1
fi
