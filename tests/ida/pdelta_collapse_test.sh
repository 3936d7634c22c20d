#!/usr/bin/env bash
# ntn-ida on the yielding portal with P-Delta (config/portal_pdelta.toml) and without it
# (config/portal_plastic.toml): the same three records, the same options and the same intensity
# measure (Sa at the portal's elastic T1 without P-Delta, 0.918 s, for both: a record is scaled by
# the same factor at a given intensity), and no drift limit (--collapse-drift none), so a run
# collapses only by an instability the model simulates: a divergence, or the stable step's bound
# of second-order geometry passed (status geometry_bound: under P-Delta the sidesway, whose results
# past the bound are not valid; the run ends there).
# With P-Delta every record has a finite collapse intensity below --max (5 g), by the geometry
# bound: the mechanism's stiffness is negative, the drift ratchets, and the columns' chord
# rotations pass the bound at about 10.8 % drift (at the model's step: config/portal_pdelta.toml's
# header says why there and how it moves with the step). Without P-Delta no record collapses up to
# --max: with linear geometry there is no such bound, and the hinges' hardening keeps the
# mechanism stable, so no run diverges. Every run is ok, but those with P-Delta at and above the
# collapse, which are geometry_bound and end before the record does.
# Prints each record's collapse intensity and the median of both models.
# usage: pdelta_collapse_test.sh NTN_IDA CONFIG_DIR SUITE_DIR OUT_DIR
set -euo pipefail
ida=$1 config=$2 suite=$3 out=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
# The suite's three shortest records (10 to 16 s), two events.
for r in PFT135.AT2 TVY045.AT2 ISE-WE.AT2; do echo "$suite/$r"; done >"$out/records.txt"
max=5
study=(--records "$out/records.txt" --period 0.91781 --collapse-drift none --max "$max"
  --first 0.25 --step-increase 0.25 --resolution 0.1 --runs 10 --tail 2 --no-plots -q)

# The two studies side by side (one process each).
"$ida" "$config/portal_pdelta.toml" "${study[@]}" --out "$out/pdelta" >"$out/pdelta.txt" 2>&1 &
with=$!
"$ida" "$config/portal_plastic.toml" "${study[@]}" --out "$out/plastic" >"$out/plastic.txt" 2>&1 &
without=$!
wait "$with" || fail "portal_pdelta: exit $?: $(cat "$out/pdelta.txt")"
wait "$without" || fail "portal_plastic: exit $?: $(cat "$out/plastic.txt")"

# capacities.csv: record,im_record[g],pga[g],io[g],ls[g],cp[g],collapse[g],highest[g],traced
# results.csv: record,im[g],scale,collapse,peak_drift[-],...,status,steps,output_hash
# With P-Delta: every record traced, with a collapse intensity in (0, max]; a run collapsed
# exactly when it passed the geometry bound, and then ended before the record's standing runs.
awk -F, -v max="$max" 'NR == 1 { next }
  { n++
    if ($9 != 1) { print $1 " not traced"; bad = 1 }
    if ($7 == "" || !($7 > 0 && $7 <= max)) {
      print $1 " has no collapse up to " max " g (highest run " $8 " g)"; bad = 1 } }
  END { if (n != 3) { print n " records, not 3"; bad = 1 }; exit bad }' \
  "$out/pdelta/capacities.csv" || fail "portal_pdelta: $(cat "$out/pdelta/capacities.csv")"
awk -F, 'NR == 1 { next }
  $NF !~ /^[0-9a-f]+$/ || length($NF) != 16 { print "no output hash: " $0; bad = 1 }
  $(NF - 2) != "ok" && $(NF - 2) != "geometry_bound" { print "status: " $0; bad = 1 }
  ($4 == 1) != ($(NF - 2) == "geometry_bound") { print "collapse and status differ: " $0; bad = 1 }
  $4 == 0 { full[$1] = $(NF - 1) }
  $4 == 1 { ended[$1] = ended[$1] " " $(NF - 1) }
  END {
    for (r in ended) {
      n = split(ended[r], s, " ")
      for (i = 1; i <= n; i++)
        if (!(s[i] < full[r])) { print r ": a collapse ran " s[i] " of " full[r] " steps"; bad = 1 }
    }
    exit bad }' "$out/pdelta/results.csv" || fail "portal_pdelta: results.csv"

# Without P-Delta: every record traced up to max without a collapse, every run ok.
awk -F, -v max="$max" 'NR == 1 { next }
  { n++
    if ($9 != 1) { print $1 " not traced"; bad = 1 }
    if ($7 != "") { print $1 " collapses at " $7 " g"; bad = 1 }
    if ($8 != max) { print $1 ": highest run " $8 " g, not " max; bad = 1 } }
  END { if (n != 3) { print n " records, not 3"; bad = 1 }; exit bad }' \
  "$out/plastic/capacities.csv" || fail "portal_plastic: $(cat "$out/plastic/capacities.csv")"
awk -F, 'NR == 1 { next }
  $NF !~ /^[0-9a-f]+$/ || length($NF) != 16 || $(NF - 2) != "ok" || $4 != 0 {
    print "a run not ok or collapsed: " $0; bad = 1 }
  END { exit bad }' "$out/plastic/results.csv" || fail "portal_plastic: results.csv"
# The summary lines: every collapse with P-Delta past the geometry bound, none without.
read -r collapsed past < <(sed -n 's/^runs [0-9]* (\([0-9]*\) collapsed, of them 0 diverged and \([0-9]*\) past the geometry bound;.*/\1 \2/p' "$out/pdelta.txt") || true
[[ -n "${collapsed:-}" && $collapsed -gt 0 && $collapsed == "$past" ]] ||
  fail "portal_pdelta: the summary: $(cat "$out/pdelta.txt")"
grep -q "runs [0-9]* (0 collapsed, of them 0 diverged and 0 past" "$out/plastic.txt" ||
  fail "portal_plastic: the summary: $(cat "$out/plastic.txt")"

# Each record's collapse intensity with and without P-Delta (the records in the same order), and
# the medians.
paste -d, <(cut -d, -f1,7 "$out/pdelta/capacities.csv") \
  <(cut -d, -f1,7,8 "$out/plastic/capacities.csv") |
  awk -F, 'NR == 1 { print "collapse Sa(0.918 s) [g]  P-Delta  without"; next }
    { if ($1 != $3) { print "records differ: " $0; exit 1 }
      printf "  %-20s %8.4g  none up to %g\n", $1, $2, $5
      v[++n] = $2 }
    END {
      for (i = 1; i <= n; i++)  # insertion sort
        for (j = i; j > 1 && v[j - 1] > v[j]; j--) { t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
      m = n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
      printf "  %-20s %8.4g  none\n", "median", m }' ||
  fail "the collapse intensities"
