#!/usr/bin/env python3
"""The default frame under El Centro from Python: load, run, peaks, drift and spectrum.

    PYTHONPATH=.build/release/python python3 tools/python/examples/el_centro.py [--out DIR]

Loads config/frame3d.toml (no compile step), runs the 1940 El Centro record (config/ground-
motions/elCentro.AT2) in the kernel, prints the output hash (the same as
`ntn-run config/frame3d.toml --input ag_x=...`), the peak drifts and the first modes against
the response's spectrum, and with matplotlib (python3-matplotlib) draws the drift history and the
roof's spectrum with the model's frequencies to DIR/el_centro.png.
"""

import argparse
import os
import sys

import numpy as np

import ntnrt

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default=os.path.join(ROOT, "config", "frame3d.toml"))
    parser.add_argument("--record",
                        default=os.path.join(ROOT, "config", "ground-motions", "elCentro.AT2"))
    parser.add_argument("--out", default=".", help="folder for el_centro.png")
    args = parser.parse_args()

    model = ntnrt.load(args.model)
    record = ntnrt.read_at2(args.record)
    print(f"model {model.name}: {model.sizes['nodes']} nodes, {model.sizes['elements']} "
          f"elements, dt = {model.dt * 1e6:.1f} us ({model.substeps} per frame)")
    result = model.run(inputs={model.inputs[0]: record})
    summary = result["summary"]
    print(f"ran {result['steps']} steps ({summary['simulated_s']:.2f} s) in "
          f"{summary['wall_s']:.2f} s; output hash {result['hash']}")

    drifts = [n for n, u in zip(model.outputs, model.units) if "drift" in n]
    for name in drifts:
        p = summary["peaks"][name]
        print(f"  peak {name:<14} {100 * p['abs']:.4f} % at t = {p['time']:.3f} s")

    # The modes the record along x excites (effective mass along x), against the roof's spectrum.
    modes = model.modes(6)
    fs = 1.0 / model.frame_period
    roof = next(n for n in model.outputs if n.startswith("roof"))
    f, psd = ntnrt.psd(result["outputs"][roof], fs, resolution=0.05)
    x_modes = []
    for k, fm in enumerate(modes["frequency"], 1):
        share = modes["effective_mass"][k - 1, 0] / modes["total_mass"][0]
        if share < 0.01:
            continue
        x_modes.append(fm)
        band = (f > 0.95 * fm) & (f < 1.05 * fm)
        seen = f[band][np.argmax(psd[band])]
        print(f"  mode {k}: {fm:.3f} Hz, {100 * share:.1f} % of the mass along x; "
              f"the roof's spectrum peaks at {seen:.3f} Hz")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not installed (python3-matplotlib): no plot")
        return 0
    fig, (a, b) = plt.subplots(2, 1, figsize=(8, 7))
    for name in drifts:
        a.plot(result["time"], 100 * result["outputs"][name], label=name, lw=0.8)
    a.set_xlabel("time [s]")
    a.set_ylabel("drift [%]")
    a.legend()
    b.semilogy(f, psd, lw=0.8)
    for fm in x_modes:
        b.axvline(fm, color="r", ls="--", lw=0.6)
    b.set_xlim(0, 3 * max(x_modes))
    b.set_xlabel("frequency [Hz]")
    b.set_ylabel(f"PSD of {roof}")
    fig.tight_layout()
    path = os.path.join(args.out, "el_centro.png")
    fig.savefig(path, dpi=120)
    print(f"plot {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
