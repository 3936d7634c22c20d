#!/usr/bin/env bash
# Hostile command-line arguments: runs the cases of one group of cases.txt and checks, for each,
# the generic rules
#   - no signal (exit code < 128) and no hang (each case under `timeout`, CASE_TIMEOUT s);
#   - no uncaught exception or sanitizer report on stderr ("terminate called", "what():",
#     "AddressSanitizer", "runtime error:", ...), and no number of 40 or more digits (CLI11
#     printing DBL_MAX in full, a message that had to be made clear);
# and the case's own expectation: the exit code, and for a non-zero one a message on stderr that
# contains the given text (the option's name or the argument; fragments joined by ' && ' must all
# appear, a fragment '!X' must not).
#
#   run_cases.sh GROUP CASES_FILE WORK_DIR SOURCE_DIR [TOOL=PATH ...]
#
# WORK_DIR (under the build tree) is emptied and holds every file a case reads or writes;
# SOURCE_DIR is the project's root (models and records). TOOL=PATH defines the placeholder @TOOL@.
# Placeholders in cases.txt (see there) are replaced before the command line is split as bash
# words (eval: the table is ours, its paths have no spaces). Prints one line per case and the
# failures with the first lines of stderr; exit 1 when a case fails.
set -u
group=$1 cases=$2 work=$3 src=$4
shift 4
timeout_s=${CASE_TIMEOUT:-120}

declare -A ph
for kv in "$@"; do ph[${kv%%=*}]=${kv#*=}; done

case $work in
  "" | / | /home* | /usr* | /etc*) echo "refusing WORK_DIR '$work'" >&2; exit 2 ;;
esac
rm -rf -- "$work"
mkdir -p -- "$work/a_dir" || exit 2
tmp=$(cd "$work" && pwd)

# Fixtures.
: >"$tmp/empty.toml"; : >"$tmp/empty.csv"; : >"$tmp/empty.AT2"; : >"$tmp/empty.log"
echo "a regular file, not a directory" >"$tmp/regular_file"
head -c 4096 /dev/zero | tr '\0' 'Z' >"$tmp/garbage.log"
# A response of the modal check's test model: 40 s at 100 Hz of its first two modes.
awk 'BEGIN { print "time[s],roof_ux[m],roof_uy[m]";
  for (k = 0; k < 4000; ++k) { t = k / 100;
    printf "%.9g,%.17g,%.17g\n", t, 1e-3 * sin(2 * 3.141592653589793 * 1.7388 * t),
      1e-3 * sin(2 * 3.141592653589793 * 1.6046 * t) } }' >"$tmp/response.csv"
# A history (ntn-plot history) and a spectrum (ntn-plot psd).
awk 'BEGIN { print "time[s],a[m]"; for (k = 0; k < 200; ++k) printf "%g,%g\n", k / 100, sin(k / 10) }' \
  >"$tmp/history.csv"
# A ground motion of 5 g at t = 0.01 s: outside frame3d's accepted range [-3, 3] g of ag_x.
printf 'time[s],ag_x[g]\n0,0\n0.01,5\n0.02,0\n' >"$tmp/out_of_range.csv"
# Record lists for ntn-ida: one short real record (10 s); a list naming a file that is not there.
printf '# one record\n%s\n' "$src/config/ground-motions/suite/PFT135.AT2" >"$tmp/one_record.txt"
printf 'no_such.AT2\n' >"$tmp/missing_record.txt"
awk 'BEGIN { print "frequency[Hz],s1[m^2/Hz]"; for (k = 1; k < 200; ++k) printf "%g,%g\n", k / 20, 1 / (1 + (k / 20 - 2) ^ 2) }' \
  >"$tmp/psd.csv"

ph[TMP]=$tmp
ph[DIR]=$tmp/a_dir
ph[FILE]=$tmp/regular_file
ph[MODEL]=$src/config/frame3d.toml
ph[CANTILEVER]=$src/config/cantilever.toml
ph[SENSORS]=$src/tests/modecheck/frame3d_sensors.toml
ph[AT2]=$src/config/ground-motions/elCentro.AT2
ph[MODELC_BAD]=$src/tests/modelc/bad
ph[REGRESSIONS]=$src/tests/fuzz/regressions

# The real-time loop's logs for replay (format 2, hil_sim/include/ntn/hil/recorder.hpp: header,
# frames, a 24-byte end record): a valid one of 3 frames, its header alone (no frames, no end
# record; header size = size(1 frame) - (size(2) - size(1)) - 24), one cut mid-frame (inside frame
# 2), one with 3 bytes after its end record, and a version-1 header (the format before checksums).
if [[ -n ${ph[ntn-hil-frame3d]:-} && ( $group == hil || $group == runtime ) ]]; then
  hil=${ph[ntn-hil-frame3d]}
  for n in 1 2 3; do
    timeout "$timeout_s" "$hil" run --clock virtual -i "ag_x=${ph[AT2]}" -n $n -q \
      --record "$tmp/log$n.log" >/dev/null 2>&1 || echo "fixture: $hil run -n $n failed" >&2
  done
  if [[ -s $tmp/log1.log && -s $tmp/log2.log ]]; then
    s1=$(stat -c %s "$tmp/log1.log") s2=$(stat -c %s "$tmp/log2.log")
    head -c $((2 * s1 - s2 - 24)) "$tmp/log1.log" >"$tmp/header_only.log"
    head -c $((s2 + (s2 - s1) / 2)) "$tmp/log3.log" >"$tmp/cut.log"
    { cat "$tmp/log3.log"; printf 'xyz'; } >"$tmp/trailing.log"
  fi
  { printf 'NTNLOG1\0\001\0\0\0'; head -c 96 /dev/zero; } >"$tmp/v1.log"
fi

pass=0 fail=0 failures=""
while IFS= read -r line; do
  [[ $line =~ ^[[:space:]]*(#|$) ]] && continue
  IFS='|' read -r g expect msg cmd <<<"$line"
  trim() { local v=$1; v=${v#"${v%%[![:space:]]*}"}; printf '%s' "${v%"${v##*[![:space:]]}"}"; }
  g=$(trim "$g"); expect=$(trim "$expect"); msg=$(trim "$msg")
  [[ $g == "$group" ]] || continue
  # @FULL_STDOUT@ (anywhere in COMMAND): the tool's standard output is /dev/full.
  stdout_to=$tmp/case.out
  if [[ $cmd == *@FULL_STDOUT@* ]]; then cmd=${cmd//@FULL_STDOUT@/}; stdout_to=/dev/full; fi
  for key in "${!ph[@]}"; do cmd=${cmd//@$key@/${ph[$key]}}; msg=${msg//@$key@/${ph[$key]}}; done
  if [[ $cmd =~ @[A-Za-z0-9_-]+@ ]]; then
    echo "SKIP  $cmd   (no ${BASH_REMATCH[0]}: tool or fixture missing)"
    failures+="  $cmd: placeholder ${BASH_REMATCH[0]} undefined"$'\n'; ((++fail)); continue
  fi
  eval "argv=( $cmd )"
  out=$tmp/case.out err=$tmp/case.err
  t0=$(date +%s%N)
  : >"$out"
  (cd "$tmp" && exec timeout -k 2 "$timeout_s" "${argv[@]}" >"$stdout_to" 2>"$err" </dev/null)
  rc=$?
  ms=$((($(date +%s%N) - t0) / 1000000))
  why=""
  if ((rc == 124 || rc == 137)) && ((ms >= timeout_s * 1000)); then
    why="hung: killed after ${timeout_s} s"
  elif ((rc >= 128)); then
    why="signal $((rc - 128)) (exit $rc)"
  elif grep -Eq 'terminate called|what\(\):|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|runtime error:' "$err"; then
    why="uncaught exception or sanitizer report (exit $rc)"
  elif grep -Eq '[0-9]{40}' "$err"; then
    why="a number printed with 40 or more digits (DBL_MAX in full?) (exit $rc)"
  elif [[ $rc != "$expect" ]]; then
    why="exit $rc, expected $expect"
  elif [[ $expect != 0 && -n $msg ]]; then
    # TEXT: fragments joined by ' && '; '!fragment' must not appear.
    rest=$msg
    while [[ -n $rest && -z $why ]]; do
      frag=${rest%% && *}
      [[ $frag == "$rest" ]] && rest="" || rest=${rest#* && }
      if [[ $frag == !* ]]; then
        grep -qF -- "${frag#!}" "$err" && why="exit $rc as expected, but stderr says '${frag#!}'"
      elif ! grep -qF -- "$frag" "$err"; then
        why="exit $rc as expected, but stderr does not name '$frag'"
      fi
    done
  fi
  short=$cmd
  for key in ntn-model ntn-modelc ntn-run-frame3d ntn-hil-frame3d ntn-feeder ntn-check-modes ntn-plot \
    ntn-run ntn-hil; do
    [[ -n ${ph[$key]:-} ]] && short=${short//${ph[$key]}/$key}
  done
  short=${short//$tmp\//}; short=${short//$src\//}
  if [[ -z $why ]]; then
    ((++pass)); printf 'ok    %5d ms  exit %-3d %s\n' "$ms" "$rc" "$short"
  else
    ((++fail)); printf 'FAIL  %5d ms  exit %-3d %s\n' "$ms" "$rc" "$short"
    first=$(head -c 600 "$err" | head -n 3 | sed 's/^/        | /')
    [[ -z $first ]] && first="        | (stderr empty; stdout: $(head -c 200 "$out" | head -n 1))"
    failures+="  $short"$'\n'"      -> $why"$'\n'"$first"$'\n'
  fi
done <"$cases"

echo
echo "robustness $group: $((pass + fail)) cases, $pass ok, $fail failed"
if ((fail > 0)); then
  echo "failed cases:"
  printf '%s' "$failures"
  exit 1
fi
((pass > 0)) || { echo "no case ran for group '$group'"; exit 1; }
