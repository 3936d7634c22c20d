#!/usr/bin/env bash
# SIGTERM and SIGINT to `ntn-run --out CSV --summary-json J` in the middle of a run: the run ends
# after the frame in progress with exit 4, the CSV whole (every row complete, the last one
# ending in a newline), the summary printed with the signal and the JSON naming it.
# Usage: stop_signal_test.sh NTN_RUN MODEL RECORD WORK_DIR
set -u
run=$1 model=$2 record=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
fail=0
for sig in TERM INT; do
  "$run" "$model" --input "ag_x=$record" --duration 1000 --out "out_$sig.csv" \
    --summary-json "s_$sig.json" >"summary_$sig.txt" 2>"err_$sig.txt" &
  pid=$!
  # Mid-run: once the first 1 MiB block of rows has reached the file (a hang detector bounds it).
  for ((i = 0; i < 6000; ++i)); do
    [[ -f out_$sig.csv ]] && (($(stat -c %s "out_$sig.csv") >= 1048576)) && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -"$sig" "$pid"
  wait "$pid"
  rc=$?
  header_fields=$(head -n 1 "out_$sig.csv" | awk -F, '{print NF}')
  bad_rows=$(awk -F, -v n="$header_fields" 'NF != n' "out_$sig.csv" | wc -l)
  last_byte=$(tail -c 1 "out_$sig.csv" | od -An -c | tr -d ' ')
  why=""
  ((rc == 4)) || why+=" exit $rc, expected 4;"
  ((bad_rows == 0)) || why+=" $bad_rows rows without $header_fields fields;"
  [[ $last_byte == '\n' ]] || why+=" the CSV does not end with a newline;"
  grep -q "STOPPED     by SIG$sig" "summary_$sig.txt" || why+=" no STOPPED line in the summary;"
  grep -q "\"stopped_by\": \"SIG$sig\"" "s_$sig.json" || why+=" the JSON does not name SIG$sig;"
  grep -q "stopped by SIG$sig after" "err_$sig.txt" || why+=" stderr does not say it stopped;"
  if [[ -n $why ]]; then
    echo "FAIL SIG$sig:$why"; cat "err_$sig.txt"; fail=1
  else
    echo "ok   SIG$sig: exit 4, $(($(wc -l <"out_$sig.csv") - 1)) whole rows"
  fi
done
exit $fail
