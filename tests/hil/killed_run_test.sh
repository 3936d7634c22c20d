#!/usr/bin/env bash
# SIGKILL (a power cut) 3 s into `ntn-hil run --clock real --record LOG --out CSV`: the log and
# the CSV hold their headers from the start and are handed to their files about once a second,
# so at least the frames up to a second before the kill are there; the log replays as a cut log
# (its complete frames, bit for bit) and the CSV's rows are whole.
# Usage: killed_run_test.sh NTN_HIL_FRAME3D RECORD WORK_DIR
set -u
hil=$1 record=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
"$hil" run --clock real -q -i "ag_x=$record" -n 30000 --record run.log --out run.csv \
  >run.txt 2>run.err &
pid=$!
sleep 3
kill -9 "$pid"
wait "$pid" 2>/dev/null
fail() { echo "FAIL: $*"; exit 1; }
[[ -s run.log ]] || fail "the log is empty after 3 s"
rows=$(($(wc -l <run.csv) - 1))
((rows >= 500)) || fail "the CSV holds $rows rows after 3 s of a 1 kHz run (wanted >= 500)"
head -n 1 run.csv | grep -q '^time\[s\]' || fail "the CSV has no header"
"$hil" replay run.log >replay.txt 2>replay.err
rc=$?
grep -q "the log is incomplete" replay.txt || fail "replay (exit $rc) does not say the log was cut: $(cat replay.txt replay.err)"
grep -q "bit-identical over" replay.txt || fail "the cut log does not replay bit for bit: $(cat replay.txt)"
echo "ok: $rows CSV rows and a log of $(stat -c %s run.log) bytes 3 s into the run; replay exit $rc"
