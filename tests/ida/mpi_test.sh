#!/usr/bin/env bash
# ntn-ida on MPI: the same small study (4 records, hunt and fill, the elasto-plastic
# column) on 1 process without mpirun and on 2, 3 and 4 processes under mpirun (oversubscribed on
# a 2-core machine) gives byte-identical results.csv, capacities.csv and fragility.csv; a study
# whose process is killed (SIGKILL) mid-run is refused without --resume and, resumed on one
# process, gives the same bytes again, reusing the runs that were done.
# usage: mpi_test.sh NTN_IDA MODEL SUITE_DIR OUT_DIR
set -euo pipefail
ida=$1 model=$2 suite=$3 out=$4
# Open MPI refuses root without these (CI runs as root) and more processes than cores without
# oversubscription.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$out"
mkdir -p "$out"
for r in PFT135.AT2 TVY045.AT2 GCN-WE.AT2 ISE-WE.AT2; do echo "$suite/$r"; done >"$out/records.txt"
study=(--records "$out/records.txt" --im pga --collapse-drift 0.05 --tail 1 --first 0.3
  --step-increase 0.3 --runs 6 --resolution 0.05 --no-plots -q)
fail() { echo "FAIL: $*" >&2; exit 1; }

"$ida" "$model" "${study[@]}" --out "$out/n1" >"$out/n1.txt"
grep -q "runs 24 " "$out/n1.txt" || fail "1 process: not 24 runs: $(cat "$out/n1.txt")"
for n in 2 3 4; do
  mpirun -np "$n" "$ida" "$model" "${study[@]}" --out "$out/n$n" >"$out/n$n.txt" ||
    fail "mpirun -np $n: exit $?: $(cat "$out/n$n.txt")"
  grep -q "on $n processes" "$out/n$n.txt" || fail "-np $n: not $n processes: $(cat "$out/n$n.txt")"
  for f in results.csv capacities.csv fragility.csv; do
    cmp "$out/n1/$f" "$out/n$n/$f" || fail "$f differs between 1 and $n processes"
  done
  # The study's time is the last process's: at least every process's own time (0.1 s for the
  # processes' start offsets and the one-decimal print).
  awk '/^time / {
         wall = $2; worst = 0
         for (i = 1; i <= NF; ++i) if ($i == "runs" && $(i + 2) ~ /^s/ && $(i + 1) + 0 > worst) worst = $(i + 1) + 0
         if (wall + 0.1 < worst) { print "time " wall " s < a process'"'"'s " worst " s"; exit 1 }
       }' "$out/n$n.txt" || fail "-np $n: the study's time is not the slowest process's: $(grep '^time' "$out/n$n.txt")"
done

# Killed mid-run: one of two processes gets SIGKILL once 3 runs are in the journal.
mpirun -np 2 "$ida" "$model" "${study[@]}" --out "$out/cut" >"$out/cut.txt" 2>&1 &
job=$!
for _ in $(seq 600); do
  lines=$( (cat "$out"/cut/runs/*.runs 2>/dev/null || true) | wc -l)
  [ "$lines" -ge 3 ] && break
  sleep 0.05
done
victim=$(pgrep -n -f -- "--out $out/cut") || fail "no process of the study to kill"
kill -9 "$victim"
if wait "$job"; then fail "the study whose process was killed ended well"; fi
[ ! -e "$out/cut/results.csv" ] || fail "a killed study wrote results.csv"
done_before=$(cat "$out"/cut/runs/*.runs | wc -l)
[ "$done_before" -lt 24 ] || fail "the kill came after every run"

# Without --resume the folder is refused; with it the study ends with the same bytes.
if "$ida" "$model" "${study[@]}" --out "$out/cut" >"$out/again.txt" 2>&1; then
  fail "an occupied --out was taken without --resume"
fi
grep -q -- "--resume" "$out/again.txt" || fail "the refusal does not say --resume: $(cat "$out/again.txt")"
"$ida" "$model" "${study[@]}" --out "$out/cut" --resume >"$out/resume.txt" ||
  fail "resume: exit $?: $(cat "$out/resume.txt")"
for f in results.csv capacities.csv fragility.csv; do
  cmp "$out/n1/$f" "$out/cut/$f" || fail "$f of the resumed study differs"
done
new=$(sed -n 's/.* \([0-9]*\) new runs.*/\1/p' "$out/resume.txt")
[ -n "$new" ] && [ "$new" -lt 24 ] || fail "the resumed study did not reuse the runs done: $(cat "$out/resume.txt")"
echo "same bytes on 1-4 processes; killed after $done_before journal lines, resumed with $new new runs"
