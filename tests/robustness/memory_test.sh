#!/usr/bin/env bash
# Models larger than the memory a process may use are refused before the memory is allocated,
# with the figure they need and what is available, never "internal error: std::bad_alloc": a
# file whose TOML tree does not fit (reading), members meshed into more elements than fit
# (compiling) and a run-time block that does not fit (ntn-run). The limit is an address-space
# limit (ulimit -v), so the machine's own memory plays no part. Release only: the sanitizers
# reserve terabytes of address space.
# usage: memory_test.sh NTN_MODEL NTN_RUN RECORD WORK_DIR
set -euo pipefail
model=$1 run=$2 record=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
# A straight line of N nodes 1000 m apart, N - 1 members of DIV elements each.
line() {
  local n=$1 div=$2
  printf '[model]\nname = "line"\ndt = "auto"\n\n[[materials]]\nid = "S"\nE = 210e9\nG = 81e9\n'
  printf 'rho = 7850.0\n\n[[sections]]\nid = "H"\nA = 1e-2\nIy = 1e-4\nIz = 1e-4\nJ = 1e-6\n\n'
  awk -v n="$n" -v div="$div" 'BEGIN {
    for (i = 0; i < n; ++i) printf "[[nodes]]\nid = %d\nxyz = [%d.0, 0.0, 0.0]\n", i, 1000 * i
    printf "[[supports]]\nnode = 0\nfix = \"all\"\n"
    for (i = 0; i + 1 < n; ++i)
      printf "[[members]]\nid = \"m%d\"\nnodes = [%d, %d]\nmaterial = \"S\"\nsection = \"H\"\ndivisions = %d\n", i, i, i + 1, div
    printf "[[inputs]]\nname = \"ag_x\"\nkind = \"ground_acceleration\"\ndirection = \"x\"\nunits = \"g\"\n"
    printf "[[outputs]]\nname = \"u\"\nkind = \"displacement\"\nnode = %d\ndof = \"ux\"\n", n - 1
  }'
}
# limited KB CMD...: runs CMD under ulimit -v KB; its exit code in $code, stderr in err.txt.
limited() {
  local kb=$1
  shift
  set +e
  (ulimit -v "$kb"; exec "$@") >out.txt 2>err.txt
  code=$?
  set -e
}
refused() {  # what: the stage's words
  ((code == 1)) || fail "$1: exit $code, not 1: $(cat err.txt)"
  ! grep -q "bad_alloc\|internal error" err.txt || fail "$1: $(cat err.txt)"
  grep -Eq "$2 needs about [0-9.]+ [kMG]B of memory \(.*\), and [0-9.]+ [kMG]B is available \(the address-space limit \(ulimit -v\)\): refused before allocating it" \
    err.txt || fail "$1: not refused with the figures: $(cat err.txt)"
}

# Reading: 100 000 members (12 MB of text, a TOML tree of about 160 MB) in 150 MB.
line 100001 1 >read.toml
limited 150000 "$model" check read.toml
refused "reading" "reading the file"
grep -q "^read.toml:1:1: error: reading the file" err.txt || fail "reading: not at read.toml:1:1"

# Compiling: 100 members of 10^6 elements each (2 kB of text; 10^8 elements, about 45 GB).
line 101 1000000 >mesh.toml
limited 2000000 "$model" check mesh.toml
refused "compiling" "compiling the model"
grep -q "100 members meshed into 100000000 elements" err.txt || fail "compiling: no counts: $(cat err.txt)"

# Running: 10^6 elements compile in about 400 MB, their run-time block takes about 750 MB more.
line 1001 1000 >run.toml
limited 900000 "$run" run.toml -i "ag_x=$record" -t 0.01 -q
((code == 1)) || fail "running: exit $code, not 1: $(cat err.txt)"
! grep -q "bad_alloc\|internal error" err.txt || fail "running: $(cat err.txt)"
grep -Eq "(the run-time storage|compiling the model) needs about|out of memory \(" err.txt ||
  fail "running: not refused with the figures: $(cat err.txt)"
echo "memory: refused before allocating: $(sed -n 's/.*error: //p' err.txt | cut -c1-120)"
