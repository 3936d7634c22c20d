#!/usr/bin/env bash
# ntn-ida on the yielding portal whose gravity system leans on it (config/portal_pdelta.toml: its
# lateral strength reaches zero at theta_0 = 7.4 % drift) and on the same portal without P-Delta,
# made here from the same file: geometry = "linear", the leaning column G a vertical spring of
# its E A / l = 210e9 x 0.02 / 4 N/m with its lumped top mass (rho A l / 2 = 314 kg), so that no
# element has second-order geometry and the masses are the same, and the damping the P-Delta
# portal's alpha and beta (2 % at its modes 1 and 2 about the preload; checked).
# Both studies: three records, the same intensity measure (Sa at the portal's first period without
# P-Delta, 2.24 s: a record is scaled by the same factor in both), no drift limit
# (--collapse-drift none: a run collapses only by an instability the model simulates, a
# divergence or the stable step's bound of second-order geometry passed, status geometry_bound).
# With P-Delta every record collapses at a finite intensity below --max (5 g): the hunt's bracket
# closes to the resolution, no run that stands has a peak drift past theta_0 (a frame past it has
# less strength than its P-Delta shear and runs away to the bound), and the IDA curve flattens:
# its drift per g between the two highest standing runs is at least 1.5 times that of the first
# run (2 to 5.5 times here; at a finer resolution the slope of intensity over drift falls below
# the 20 % of the elastic slope that FEMA 350 and Vamvatsikos and Cornell take for the flatline).
# Without P-Delta no record collapses up to --max, though its drifts there are far past theta_0.
# Every run is ok but those with P-Delta that collapse, which are geometry_bound and end before
# the record does.
# The records: the suite's three shortest whose high-pass corner (0.2, 0.3 and 0.1 Hz) keeps the
# record's content at 2.24 s, three events. At half the model's step (and a 10 s tail) the
# collapse intensities are the same; too slow for this test, config/portal_pdelta.toml says so.
# Prints each record's collapse intensity, its highest standing run and drift, the drift without
# P-Delta at 5 g, and the medians. About 40 s on 2 cores.
# usage: pdelta_collapse_test.sh NTN_IDA NTN_MODEL CONFIG_DIR SUITE_DIR OUT_DIR
set -euo pipefail
ida=$1 model=$2 config=$3 suite=$4 out=$5
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
pdelta=$config/portal_pdelta.toml linear=$out/portal_linear.toml
theta0=0.074 max=5 resolution=0.01

# The portal with P-Delta: its damping, 2 % at modes 1 and 2 about the preload (with P-Delta),
# as C = alpha M + beta K; its first period without P-Delta (K alone, ntn-model info's line).
"$model" info "$pdelta" >"$out/pdelta_info.txt" || fail "ntn-model info $pdelta"
grep -q '^geometry  *12 p_delta element(s), 1 leaning column(s)' "$out/pdelta_info.txt" ||
  fail "portal_pdelta: not 12 p_delta elements and 1 leaning column: $(cat "$out/pdelta_info.txt")"
number='\([0-9.e+-]*\)'
read -r alpha beta < <(sed -n "s/^damping .* alpha = $number 1\/s, beta = $number s: 2 % at .* (modes 1 and 2)\$/\\1 \\2/p" \
  "$out/pdelta_info.txt") || fail "portal_pdelta: no damping line"
read -r f_with f1 < <(sed -n "s/^ *lowest frequency $number Hz about the preload with P-Delta, $number Hz without.*/\\1 \\2/p" \
  "$out/pdelta_info.txt") || fail "portal_pdelta: no lowest-frequency line"

# The portal without P-Delta: the model's geometry key, the paragraph with the leaning column and
# the damping (the same alpha and beta), each replaced exactly once.
awk -v RS= -v ORS='\n\n' -v alpha="$alpha" -v beta="$beta" '
  /\n\[\[leaning_columns\]\]\n/ {
    print "[[hinges]]\nid = \"G\"\nnodes = [6, \"ground\"]\nux = \"free\"" \
          "\nuz = { linear = 1.05e9 }\nry = \"free\"\n\n[[point_masses]]\nnode = 6\nmass = 314.0"
    g++; next }
  /^\[model\.damping\]\n/ { print "[model.damping]\nalpha = " alpha "\nbeta = " beta; d++; next }
  { m += sub(/\ngeometry = "p_delta"\n/, "\ngeometry = \"linear\"\n"); print }
  END { if (g != 1 || m != 1 || d != 1) {
    print "replaced " g " leaning columns, " m " geometry keys, " d " damping tables" >"/dev/stderr"
    exit 1 } }' \
  "$pdelta" >"$linear" || fail "making the portal without P-Delta"
"$model" info "$linear" >"$out/linear_info.txt" || fail "ntn-model info $linear"
! grep -q '^geometry' "$out/linear_info.txt" ||
  fail "the portal without P-Delta has second-order geometry: $(cat "$out/linear_info.txt")"
grep -q "^damping .* alpha = $alpha 1/s, beta = $beta s" "$out/linear_info.txt" ||
  fail "the portal without P-Delta: not alpha = $alpha, beta = $beta: $(grep '^damping' "$out/linear_info.txt")"
awk -v a="$f_with" -v b="$f1" 'BEGIN { exit !(a < b) }' ||
  fail "P-Delta does not lower the first frequency: $f_with Hz with, $f1 Hz without"
period=$(awk -v f="$f1" 'BEGIN { printf "%.5g", 1 / f }')
[[ $period == 2.24* ]] || fail "the first period is $period s, not 2.24 s"

for r in PFT135.AT2 GCN-WE.AT2 PBFEAS.AT2; do echo "$suite/$r"; done >"$out/records.txt"
study=(--records "$out/records.txt" --period "$period" --collapse-drift none --max "$max"
  --first 0.05 --step-increase 0.5 --resolution "$resolution" --tail 2 --no-plots -q)
# The two studies side by side (one process each). The hunt reaches 5 g in 6 runs (0.05, 0.1,
# 0.65, 1.7, 3.25, 5 g); with P-Delta it stops at its first collapse (0.65 g) and 6 bisections
# close the bracket to the resolution.
"$ida" "$pdelta" "${study[@]}" --runs 9 --out "$out/pdelta" >"$out/pdelta.txt" 2>&1 &
with=$!
"$ida" "$linear" "${study[@]}" --runs 6 --out "$out/linear" >"$out/linear.txt" 2>&1 &
without=$!
wait "$with" || fail "portal_pdelta: exit $?: $(cat "$out/pdelta.txt")"
wait "$without" || fail "portal without P-Delta: exit $?: $(cat "$out/linear.txt")"

columns='record,im[g],scale,collapse,peak_drift[-],residual_drift[-],hinge_level[-]'
columns+=',status,steps,output_hash'
for s in pdelta linear; do
  [[ $(head -1 "$out/$s/results.csv") == "$columns" ]] || fail "$s: results.csv's columns"
done
# capacities.csv: record,im_record[g],pga[g],io[g],ls[g],cp[g],collapse[g],highest[g],traced
# With P-Delta: every record traced, with a collapse intensity in (0, max].
awk -F, -v max="$max" 'NR == 1 { next }
  { n++
    if ($9 != 1) { print $1 " not traced"; bad = 1 }
    if ($7 == "" || !($7 > 0 && $7 <= max)) {
      print $1 " has no collapse up to " max " g (highest run " $8 " g)"; bad = 1 } }
  END { if (n != 3) { print n " records, not 3"; bad = 1 }; exit bad }' \
  "$out/pdelta/capacities.csv" || fail "portal_pdelta: $(cat "$out/pdelta/capacities.csv")"
# Its runs: a run collapsed exactly when it passed the geometry bound, and then ended before the
# record's standing runs; a standing run stayed inside theta_0; the bracket is closed; the curve
# flattens. Per record (the suite's order): the lowest collapse, the highest standing run and its
# drift.
awk -F, -v theta0="$theta0" -v res="$resolution" 'NR == 1 { next }
  !($1 in low) { order[++n] = $1; low[$1] = 1e300; top[$1] = 0; first[$1] = 1e300 }
  $NF !~ /^[0-9a-f]+$/ || length($NF) != 16 { print "no output hash: " $0; bad = 1 }
  $8 != "ok" && $8 != "geometry_bound" { print "status: " $0; bad = 1 }
  ($4 == 1) != ($8 == "geometry_bound") { print "collapse and status differ: " $0; bad = 1 }
  $4 == 1 { ended[$1] = ended[$1] " " $9; if ($2 < low[$1]) low[$1] = $2 }
  $4 == 0 {
    full[$1] = $9
    if ($5 >= theta0) { print "stands past theta_0: " $0; bad = 1 }
    if ($2 > top[$1]) {
      next_top[$1] = top[$1]; next_drift[$1] = drift[$1]; top[$1] = $2; drift[$1] = $5
    } else if ($2 > next_top[$1]) { next_top[$1] = $2; next_drift[$1] = $5 }
    if ($2 < first[$1]) { first[$1] = $2; first_drift[$1] = $5 } }
  END {
    for (i = 1; i <= n; i++) {
      r = order[i]
      k = split(ended[r], s, " ")
      for (j = 1; j <= k; j++)
        if (!(s[j] < full[r])) { print r ": a collapse ran " s[j] " of " full[r] " steps"; bad = 1 }
      if (!(low[r] - top[r] <= res * (1 + 1e-9))) {
        print r ": stands at " top[r] " g, collapses at " low[r] " g"; bad = 1 }
      slope = (drift[r] - next_drift[r]) / (top[r] - next_top[r])
      if (!(next_top[r] > first[r] && slope > 1.5 * first_drift[r] / first[r])) {
        print r ": no flattening: " 100 * first_drift[r] " % at " first[r] " g, then " \
              100 * slope " % per g from " next_top[r] " to " top[r] " g"; bad = 1 }
      print r "," low[r] "," top[r] "," drift[r] > "/dev/stderr"
    }
    exit bad }' "$out/pdelta/results.csv" 2>"$out/pdelta_records.csv" ||
  fail "portal_pdelta: results.csv"

# Without P-Delta: every record traced up to max without a collapse, every run ok.
awk -F, -v max="$max" 'NR == 1 { next }
  { n++
    if ($9 != 1) { print $1 " not traced"; bad = 1 }
    if ($7 != "") { print $1 " collapses at " $7 " g"; bad = 1 }
    if ($8 != max) { print $1 ": highest run " $8 " g, not " max; bad = 1 } }
  END { if (n != 3) { print n " records, not 3"; bad = 1 }; exit bad }' \
  "$out/linear/capacities.csv" || fail "portal without P-Delta: $(cat "$out/linear/capacities.csv")"
awk -F, -v max="$max" -v theta0="$theta0" 'NR == 1 { next }
  $NF !~ /^[0-9a-f]+$/ || length($NF) != 16 || $8 != "ok" || $4 != 0 {
    print "a run not ok or collapsed: " $0; bad = 1 }
  !($1 in seen) { seen[$1] = 1; order[++n] = $1 }
  $2 == max { at_max[$1] = $5; if ($5 <= theta0) { print "inside theta_0 at max: " $0; bad = 1 } }
  END { for (i = 1; i <= n; i++) print order[i] "," at_max[order[i]] > "/dev/stderr"; exit bad }' \
  "$out/linear/results.csv" 2>"$out/linear_records.csv" ||
  fail "portal without P-Delta: results.csv"
# The summary lines: every collapse with P-Delta past the geometry bound, none without.
read -r collapsed past < <(sed -n 's/^runs [0-9]* (\([0-9]*\) collapsed, of them 0 diverged and \([0-9]*\) past the geometry bound;.*/\1 \2/p' "$out/pdelta.txt") || true
[[ -n "${collapsed:-}" && $collapsed -gt 0 && $collapsed == "$past" ]] ||
  fail "portal_pdelta: the summary: $(cat "$out/pdelta.txt")"
grep -q "runs [0-9]* (0 collapsed, of them 0 diverged and 0 past" "$out/linear.txt" ||
  fail "portal without P-Delta: the summary: $(cat "$out/linear.txt")"

# Each record with and without P-Delta (the records in the same order), and the medians.
paste -d, "$out/pdelta_records.csv" "$out/linear_records.csv" |
  awk -F, -v T="$period" -v max="$max" '
    BEGIN {
      printf "Sa(%s s) [g]   P-Delta: collapse  stands (drift)    without: drift at %g g\n", T, max }
    { if ($1 != $5) { print "records differ: " $0; exit 1 }
      printf "  %-12s %17.4g  %6.4g (%5.2f %%)  %9.1f %%\n", $1, $2, $3, 100 * $4, 100 * $6
      c[++n] = $2; d[n] = 100 * $4; e[n] = 100 * $6 }
    function median(v, n,   i, j, t) {
      for (i = 1; i <= n; i++)  # insertion sort
        for (j = i; j > 1 && v[j - 1] > v[j]; j--) { t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
      return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2 }
    END {
      printf "  %-12s %17.4g  %6s (%5.2f %%)  %9.1f %%\n", "median", median(c, n), "", median(d, n),
             median(e, n) }' ||
  fail "the collapse intensities"
