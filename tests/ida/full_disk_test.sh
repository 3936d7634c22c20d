#!/usr/bin/env bash
# ntn-ida when the disk will not take its files: a file size limit (ulimit -f, SIGXFSZ ignored,
# so every write past it fails as on a full disk, for ntn-ida and the gnuplot it runs) cuts the
# journal, results.csv and the plots. Nothing partial is left (no cut file, no part file, no
# journal line cut short), the exit code says what was lost (2: a result, 3: only plots) and
# a resume without the limit gives the bytes of a study that was never cut.
# usage: full_disk_test.sh NTN_IDA MODEL RECORD OUT_DIR
set -euo pipefail
ida=$1 model=$2 record=$3 out=$4
rm -rf "$out"
mkdir -p "$out"
echo "$record" >"$out/records.txt"
study=(--records "$out/records.txt" --tail 0 --runs 12 -q)
fail() { echo "FAIL: $*" >&2; exit 1; }
# Runs ntn-ida with files limited to $1 KiB; its exit code in $code, its stderr in $out/err.
limited() {
  local kib=$1
  shift
  set +e
  (trap '' XFSZ; ulimit -f "$kib"; exec "$ida" "$model" "${study[@]}" "$@") >"$out/log" 2>"$out/err"
  code=$?
  set -e
}
partial() { find "$1" \( -name '*.tmp' -o -name '*.part.*' -o -name '*.gp' -o -name '*.dat' \); }

"$ida" "$model" "${study[@]}" --out "$out/whole" >"$out/whole.log" ||
  fail "the study without a limit: $(cat "$out/whole.log")"
size=$(stat -c %s "$out/whole/results.csv")
journal=$(stat -c %s "$out"/whole/runs/*.runs)
png=$(stat -c %s "$out/whole/ida.png")
((size > 1024 && journal > 1024 && png > 8192)) ||
  fail "the study is too small for the limits below: results $size, journal $journal, png $png bytes"

# 1 KiB: results.csv and the journal do not fit.
limited 1 --out "$out/cut"
((code == 2)) || fail "1 KiB: exit $code, not 2: $(cat "$out/err")"
grep -q "cannot write '$out/cut/results.csv': File too large" "$out/err" ||
  fail "1 KiB: no error for results.csv: $(cat "$out/err")"
grep -Eq "runs are not in the journal \(File too large\): --resume would make them again" \
  "$out/err" || fail "1 KiB: the lost journal lines are not reported: $(cat "$out/err")"
grep -q "plots not made" "$out/err" || fail "1 KiB: no word on the plots: $(cat "$out/err")"
[[ ! -e $out/cut/results.csv && ! -e $out/cut/ida.png && ! -e $out/cut/ida.svg ]] ||
  fail "1 KiB: a result or plot file was left: $(ls "$out/cut")"
[[ -z $(partial "$out/cut") ]] || fail "1 KiB: partial files left: $(partial "$out/cut")"
# The journal holds whole lines only: a resume takes every one and refuses none.
lines=$(cat "$out"/cut/runs/*.runs | wc -l)
((lines > 0)) || fail "1 KiB: the journal kept no line before the limit"
[[ $(tail -c 1 "$out"/cut/runs/*.runs | od -An -c | tr -d ' ') == '\n' ]] ||
  fail "1 KiB: the journal ends in a cut line"
"$ida" "$model" "${study[@]}" --out "$out/cut" --resume >"$out/resume.log" 2>&1 ||
  fail "resume: $(cat "$out/resume.log")"
total=$(sed -n 's/^runs \([0-9]*\) .*/\1/p' "$out/whole.log")
grep -q " $((total - lines)) new runs" "$out/resume.log" ||
  fail "resume: not $total - $lines new runs: $(grep '^time' "$out/resume.log")"
for f in results.csv capacities.csv fragility.csv; do
  cmp "$out/whole/$f" "$out/cut/$f" || fail "resumed: $f differs from the study never cut"
done

# 8 KiB: every result fits, the plots do not (gnuplot cuts them and exits 0).
limited 8 --out "$out/plots"
((code == 3)) || fail "8 KiB: exit $code, not 3: $(cat "$out/err")"
grep -q "plots not made: $out/plots/ida.png: gnuplot wrote only the first" "$out/err" ||
  fail "8 KiB: the cut plot is not named: $(cat "$out/err")"
for f in results.csv capacities.csv fragility.csv; do
  cmp "$out/whole/$f" "$out/plots/$f" || fail "8 KiB: $f differs"
done
[[ ! -e $out/plots/ida.png && ! -e $out/plots/ida.svg ]] || fail "8 KiB: a cut plot was left"
[[ -z $(partial "$out/plots") ]] || fail "8 KiB: partial files left: $(partial "$out/plots")"
echo "full disk: exit 2 with $lines whole journal lines kept, exit 3 for the plots; nothing partial"
