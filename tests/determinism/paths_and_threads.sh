#!/usr/bin/env bash
# paths_and_threads.sh: one runner on the first 10 s of RECORD (the strong motion) by the SIMD and
# the scalar element and DOF passes, each with 1, 2 and 3 workers of the multi-core step: every
# run must print the same output hash and write the same CSV byte for byte (kernel/README.md: both
# paths and any team give the same bits). Three workers on a 2-CPU machine are slow but must
# still be exact.
#   paths_and_threads.sh RUNNER RECORD WORK
set -euo pipefail
runner=$1 record=$2 work=$3
mkdir -p "$work"
trap 'rm -f "$work"/*.csv' EXIT
ref=""
for pass in simd scalar; do
  for threads in 1 2 3; do
    csv="$work/$pass-$threads.csv"
    hash=$("$runner" -q --input "ag_x=$record" --duration 10 --out "$csv" --element-pass "$pass" \
      --threads "$threads" 2>/dev/null | grep 'output hash')
    if [ -z "$ref" ]; then
      ref=$hash
      cp "$csv" "$work/reference.csv"
    fi
    if [ "$hash" = "$ref" ] && cmp -s "$work/reference.csv" "$csv"; then
      echo "same  $pass, $threads thread(s):$hash"
    else
      echo "DIFF  $pass, $threads thread(s):$hash (first run:$ref)"
      exit 1
    fi
  done
done
