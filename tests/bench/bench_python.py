#!/usr/bin/env python3
"""The Python module's run() against the C++ loop it calls.

    PYTHONPATH=.build/release/python python3 tests/bench/bench_python.py [--repeats 7]

For the default frame under El Centro: the wall time of model.run() as Python sees it, the loop's
own time inside it (summary wall_s: ntn::run::simulate's run_loop, the same as ntn-run's "wall"),
and their difference per kernel step: what Python adds (converting the record, building the
numpy arrays of every frame's outputs). Also ntn-run's wall for the same run when --ntn-run is
given. Medians of --repeats runs, interleaved.
"""

import argparse
import os
import statistics
import subprocess
import time

import ntnrt

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=7)
    p.add_argument("--ntn-run", default="")
    a = p.parse_args()
    model = ntnrt.load(os.path.join(ROOT, "config", "frame3d.toml"))
    record = ntnrt.read_at2(os.path.join(ROOT, "config", "ground-motions", "elCentro.AT2"))
    py, loop, cli, steps = [], [], [], 0
    for _ in range(a.repeats):
        t0 = time.perf_counter()
        r = model.run(inputs={"ag_x": record})
        py.append(time.perf_counter() - t0)
        loop.append(r["summary"]["wall_s"])
        steps = r["steps"]
        if a.ntn_run:
            out = subprocess.run([a.ntn_run, os.path.join(ROOT, "config", "frame3d.toml"),
                                  "--input", "ag_x=" + record.source],
                                 check=True, capture_output=True, text=True).stdout
            cli.append(float(out.split("wall ")[1].split(" s")[0]))
    m_py, m_loop = statistics.median(py), statistics.median(loop)
    print(f"frame3d, El Centro: {steps} steps, {a.repeats} runs, medians (fastest in brackets)")
    print(f"  run() wall              {m_py:.4f} s  ({1e9 * m_py / steps:.1f} ns/step) "
          f"[{min(py):.4f} s]")
    print(f"  its loop (C++)          {m_loop:.4f} s  ({1e9 * m_loop / steps:.1f} ns/step) "
          f"[{min(loop):.4f} s]")
    print(f"  Python's part per step  {1e9 * (m_py - m_loop) / steps:.1f} ns "
          f"({100 * (m_py - m_loop) / m_loop:.1f} % of the loop)")
    if cli:
        m_cli = statistics.median(cli)
        print(f"  ntn-run's loop          {m_cli:.4f} s  ({1e9 * m_cli / steps:.1f} ns/step) "
              f"[{min(cli):.4f} s]")
        print(f"  run()'s loop / ntn-run's: {m_loop / m_cli:.3f}")


if __name__ == "__main__":
    main()
