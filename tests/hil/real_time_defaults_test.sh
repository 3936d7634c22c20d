#!/usr/bin/env bash
# `ntn-hil run --clock real` and `ntn-feeder` ask for what a real-time run needs without being
# told: SCHED_FIFO, locked memory, a timer slack of 1 ns and a CPU wake-up latency of 0 us. Read
# from /proc while the loop runs (the system's word, not the program's), each is granted or
# refused with a warning that names it, and the summary says which; the opt-outs give a normal
# thread and no warning. Holds whatever the machine permits (root or not).
# usage: real_time_defaults_test.sh NTN_HIL MODEL RECORD NTN_FEEDER WORK_DIR
set -euo pipefail
hil=$1 model=$2 record=$3 feeder=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
run=(run "$model" -i "ag_x=$record")

# Defaults: sampled from /proc 1 s into a 3 s run.
"$hil" "${run[@]}" -n 3000 --summary-json d.json >d.txt 2>d.err &
pid=$!
sleep 1
policy=$(awk '{ print $41 }' "/proc/$pid/stat")           # 1: SCHED_FIFO
priority=$(awk '{ print $40 }' "/proc/$pid/stat")         # rt_priority
locked=$(awk '/^VmLck:/ { print $2 }' "/proc/$pid/status") # kB
slack=$(cat "/proc/$pid/timerslack_ns" 2>/dev/null || echo "?")
wait "$pid" || fail "the default run: exit $?: $(cat d.err)"
if grep -q "SCHED_FIFO not permitted" d.err; then
  ((policy == 0)) || fail "FIFO refused, yet the policy is $policy"
  grep -q '"fifo": false' d.json || fail "FIFO refused, the summary says otherwise"
  grep -q "normal scheduling" d.txt || fail "the summary does not say normal scheduling"
else
  ((policy == 1 && priority == 80)) || fail "no SCHED_FIFO 80 and no warning: policy $policy priority $priority"
  grep -q '"fifo": true, "priority": 80' d.json || fail "the summary does not report FIFO 80"
  grep -q "real time: SCHED_FIFO 80" d.txt || fail "no 'real time: SCHED_FIFO 80' line: $(cat d.txt)"
fi
if grep -q "mlockall not permitted" d.err; then
  grep -q '"memory_locked": false' d.json || fail "mlockall refused, the summary says otherwise"
else
  ((locked > 0)) || fail "memory not locked (VmLck $locked kB) and no warning"
  grep -q '"memory_locked": true' d.json || fail "the summary does not report locked memory"
fi
# The timer slack is the thread's own to set: never refused (/proc shows the main thread's). A
# SCHED_FIFO thread has none: recent kernels show 0 for it.
[[ $slack == "?" || $slack == 1 || ($slack == 0 && $policy == 1) ]] ||
  fail "timer slack $slack ns, not 1 (policy $policy)"
grep -Eq '"timer_slack_ns": (1|0),' d.json || fail "the summary's timer slack: $(grep real_time d.json)"
grep -q "CPU latency 0 us not set" d.err || grep -q '"cpu_latency_us": 0,' d.json ||
  fail "the CPU latency neither held nor warned about"

# Opted out: a normal thread with the system's slack, nothing asked, nothing warned.
"$hil" "${run[@]}" -n 3000 --no-fifo --no-mlock --cpu-latency -1 --timer-slack 0 \
  --summary-json o.json >o.txt 2>o.err &
pid=$!
sleep 1
policy=$(awk '{ print $41 }' "/proc/$pid/stat")
slack=$(cat "/proc/$pid/timerslack_ns" 2>/dev/null || echo "?")
wait "$pid" || fail "the opted-out run: exit $?: $(cat o.err)"
((policy == 0)) || fail "--no-fifo: policy $policy"
[[ $slack == "?" || $slack -gt 1 ]] || fail "--timer-slack 0: slack $slack ns, not the default"
[[ ! -s o.err ]] || fail "opted out, yet warnings: $(cat o.err)"
grep -q '"fifo": false, "priority": 0, "memory_locked": false' o.json ||
  fail "the opted-out summary: $(grep real_time o.json)"
grep -q '"cpu_latency_us": -1' o.json || fail "--cpu-latency -1: $(grep real_time o.json)"

# The virtual clock asks for nothing.
"$hil" "${run[@]}" --clock virtual -n 100 --summary-json v.json >v.txt 2>v.err
grep -q '"real_time": null' v.json || fail "the virtual clock: $(grep real_time v.json)"
[[ ! -s v.err ]] || fail "the virtual clock warned: $(cat v.err)"

# The feeder's real time: the same defaults one priority step below the loop (70).
"$feeder" --port 9 --record "$record" --frames 200 --linger 0 >f.txt 2>f.err ||
  fail "the feeder: exit $?: $(cat f.err)"
grep -q "SCHED_FIFO not permitted" f.err || grep -q "real time   SCHED_FIFO 70" f.txt ||
  fail "the feeder neither ran at FIFO 70 nor warned: $(grep 'real time' f.txt)"
grep -Eq "timer slack (1|0) ns" f.txt || fail "the feeder's timer slack: $(grep 'real time' f.txt)"
echo "real-time defaults: $(grep 'real time:' d.txt | sed 's/^ *//')"
