#!/usr/bin/env bash
# Wake-up latency of `ntn-hil run --clock real` at 1 kHz against the platform's, measured one
# after the other in one run: cyclictest (rt-tests) at SCHED_FIFO 80 with memory locked (the
# floor of this machine), cyclictest as a normal thread, and ntn-hil with its real-time defaults
# (SCHED_FIFO 80, mlockall, timer slack 1 ns, CPU latency 0 us as cyclictest holds it), with
# FIFO and the CPU latency turned off (timer slack 1 ns alone: what an unprivileged user gets)
# and with everything turned off (a normal thread's 50 us slack). Prints a table of medians and
# 99th percentiles in us.
# usage: tests/bench/wakeup_latency.sh [BUILD_DIR] [SECONDS]   (root for SCHED_FIFO and mlockall)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${1:-$root/.build/release}
seconds=${2:-10}
# shellcheck source=../../tools/common.sh
source "$root/tools/common.sh"
ntn_install_missing rt-tests
hil=$build/hil_sim/ntn-hil
[[ -x $hil ]] || { echo "no $hil: build the release preset first" >&2; exit 1; }
loops=$((seconds * 1000))
record=$root/config/ground-motions/elCentro.AT2

# cyclictest ARGS...: "p50 p99" in us from its histogram (one thread, 1 kHz).
cyclic() {
  cyclictest -q -i 1000 -l "$loops" -h 5000 "$@" 2>/dev/null | awk '
    /^[0-9]/ { n[$1 + 0] = $2 + 0; total += $2 }
    END {
      for (us = 0; us <= 5000; ++us) {
        seen += n[us]
        if (!p50 && seen >= 0.50 * total) p50 = us
        if (!p99 && seen >= 0.99 * total) p99 = us
      }
      printf "%d %d\n", p50, p99
    }'
}
# hil ARGS...: "p50 p99" in us from ntn-hil's summary.
hil_run() {
  "$hil" run "$root/config/frame3d.toml" -i "ag_x=$record" -n "$loops" "$@" 2>/dev/null |
    awk '/wake-up latency/ { print $4, $7 }'
}

cpu=$(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -n 1)
echo "wake-up latency at 1 kHz, $seconds s each, one after the other: $cpu, $(nproc) CPUs"
printf '| %-62s | %8s | %8s |\n' "run" "p50 [us]" "p99 [us]"
printf '|%s|%s|%s|\n' "$(printf -- '-%.0s' {1..64})" "----------" "----------"
row() { printf '| %-62s | %8s | %8s |\n' "$1" "$2" "$3"; }
read -r a b < <(cyclic -m -p 80)
row "cyclictest -m -p 80 (the platform)" "$a" "$b"
read -r a b < <(hil_run)
row "ntn-hil run --clock real (its defaults)" "$a" "$b"
read -r a b < <(hil_run --no-fifo --no-mlock --cpu-latency -1)
row "ntn-hil ... --no-fifo --no-mlock --cpu-latency -1 (slack 1 ns)" "$a" "$b"
read -r a b < <(cyclic)
row "cyclictest, a normal thread" "$a" "$b"
read -r a b < <(hil_run --no-fifo --no-mlock --cpu-latency -1 --timer-slack 0)
row "ntn-hil ... and --timer-slack 0 (a normal thread)" "$a" "$b"
