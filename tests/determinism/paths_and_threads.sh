#!/usr/bin/env bash
# paths_and_threads.sh: one runner on El Centro by the SIMD and the scalar element and DOF passes,
# each with 1, 2 and 3 workers of the multi-core step: every run must give the same bits
# (kernel/README.md: both paths and any team give the same bits).
#   - 1 and 2 workers run the first 10 s (the strong motion) and must print the output hash of the
#     first run and write its CSV byte for byte;
#   - 3 workers run the first 3 s and must write the first 3 s of that CSV byte for byte (every
#     channel at 17 significant digits: the same doubles). Three workers on a 2-CPU machine hand
#     each phase to a worker that has no CPU (~20x slower per step), so they run the shorter
#     stretch; the 3-worker partition is uneven either way.
# CTest gives this test both CPUs (PROCESSORS 2): a team that shares its CPUs with another test
# is as slow as the 3-worker one.
#   paths_and_threads.sh RUNNER RECORD WORK
set -euo pipefail
runner=$1 record=$2 work=$3
mkdir -p "$work"
trap 'rm -f "$work"/*.csv' EXIT
ref=""
for pass in simd scalar; do
  for threads in 1 2 3; do
    csv="$work/$pass-$threads.csv"
    duration=10
    [ "$threads" -eq 3 ] && duration=3
    hash=$("$runner" -q --input "ag_x=$record" --duration "$duration" --out "$csv" \
      --element-pass "$pass" --threads "$threads" 2>/dev/null | grep 'output hash')
    if [ -z "$ref" ]; then
      ref=$hash
      cp "$csv" "$work/reference.csv"
    fi
    if [ "$duration" -eq 10 ]; then
      if [ "$hash" = "$ref" ] && cmp -s "$work/reference.csv" "$csv"; then
        echo "same  $pass, $threads thread(s), 10 s:$hash"
      else
        echo "DIFF  $pass, $threads thread(s), 10 s:$hash (first run:$ref)"
        exit 1
      fi
    else
      rows=$(wc -l <"$csv")
      if [ "$rows" -gt 2000 ] && head -n "$rows" "$work/reference.csv" | cmp -s - "$csv"; then
        echo "same  $pass, $threads thread(s), 3 s: the first $rows lines of the first run's CSV"
      else
        echo "DIFF  $pass, $threads thread(s), 3 s: not the first $rows lines of the first run's CSV"
        exit 1
      fi
    fi
  done
done
