"""The Python module ntnrt, run by CTest (tests/python/CMakeLists.txt).

Truth that no one here chose: the command-line tools' output hashes and CSV bytes (the module
must equal them bit for bit), the El Centro reference hash, the Euler-Bernoulli cantilever's
closed form for the modes, Parseval's theorem for the PSD, and a run that is interrupted and
restored equal to one that is not.
"""

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import ntnrt

CONFIG = os.environ["NTN_CONFIG_DIR"]
EL_CENTRO = os.path.join(CONFIG, "ground-motions", "elCentro.AT2")
NTN_RUN = os.environ["NTN_RUN"]  # ntn-run MODEL.toml
RUNNERS = os.environ["NTN_RUNNERS"]  # the folder of the compiled ntn-run-<model>
CHECK_MODES = os.environ["NTN_CHECK_MODES"]
EXAMPLE = os.environ["NTN_EXAMPLE"]

# ntn-run-frame3d on El Centro since damping_velocity = "central" (tests/tools/runner_test.cmake).
FRAME3D_EL_CENTRO = "6e2293debe9ca748"


def cli_hash(args):
    out = subprocess.run(args + ["-q"], check=True, capture_output=True, text=True).stdout
    return out.split("output hash")[1].split()[0]


@pytest.fixture(scope="module")
def frame3d():
    return ntnrt.load(os.path.join(CONFIG, "frame3d.toml"))


@pytest.fixture(scope="module")
def el_centro():
    return ntnrt.read_at2(EL_CENTRO)


def test_load_gives_the_model(frame3d):
    assert frame3d.name == "frame3d"
    sizes = frame3d.sizes
    assert sizes["nodes"] == frame3d.nodes.shape[0] and frame3d.nodes.shape[1] == 3
    assert sizes["dofs"] == 6 * sizes["nodes"]
    assert frame3d.inputs == ["ag_x"]
    assert len(frame3d.outputs) == sizes["outputs"] == len(frame3d.units)
    assert 0 < frame3d.dt <= frame3d.stable_dt
    assert frame3d.substeps * frame3d.dt == pytest.approx(frame3d.frame_period, rel=1e-12)
    info = frame3d.info()  # what `ntn-model info` prints
    assert "stable dt" in info and "frame3d" in info


def test_load_error_names_file_line_column_and_key(tmp_path):
    text = open(os.path.join(CONFIG, "cantilever.toml")).read()
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("E = 210e9", "E = -210e9"))
    line = next(i for i, l in enumerate(text.splitlines(), 1) if l.startswith("E = 210e9"))
    with pytest.raises(ntnrt.ModelError) as e:
        ntnrt.load(str(bad))
    assert f"bad.toml:{line}:" in str(e.value)
    assert "E" in str(e.value)
    with pytest.raises(ntnrt.ModelError):
        ntnrt.load(str(tmp_path / "missing.toml"))


def test_run_equals_the_command_line(frame3d, el_centro, tmp_path):
    r = frame3d.run(inputs={"ag_x": el_centro})
    assert r["hash"] == FRAME3D_EL_CENTRO
    assert r["hash"] == cli_hash([NTN_RUN, os.path.join(CONFIG, "frame3d.toml"),
                                  "--input", "ag_x=" + EL_CENTRO])
    assert not r["diverged"]
    # Every frame's outputs equal the CLI's CSV (written with %.17g: exact) value for value.
    csv = tmp_path / "frame3d.csv"
    subprocess.run([os.path.join(RUNNERS, "ntn-run-frame3d"), "--input", "ag_x=" + EL_CENTRO,
                    "--out", str(csv), "-q"], check=True, capture_output=True)
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert table.shape[0] == r["time"].size
    assert np.allclose(table[:, 0], r["time"], rtol=0, atol=1e-9)  # %.9g in the CSV
    for c, name in enumerate(frame3d.outputs):
        assert np.array_equal(table[:, c + 1], r["outputs"][name]), name
    # Two threads and the scalar element pass: the same bits.
    assert frame3d.run(inputs={"ag_x": el_centro}, threads=2)["hash"] == FRAME3D_EL_CENTRO
    assert frame3d.run(inputs={"ag_x": el_centro},
                       element_pass="scalar")["hash"] == FRAME3D_EL_CENTRO


def test_corotational_mast_equals_the_command_line(el_centro):
    # Corotational members (the nodes' rotations in the run's State) and a yielding base plate,
    # the first 10 s of El Centro: the command line's bits, on one and two threads; the stable
    # step's bound held.
    path = os.path.join(CONFIG, "mast.toml")
    model = ntnrt.load(path)
    r = model.run(inputs={"ag_x": el_centro}, duration=10.0)
    assert r["hash"] == cli_hash([NTN_RUN, path, "--input", "ag_x=" + EL_CENTRO,
                                  "--duration", "10"])
    assert model.run(inputs={"ag_x": el_centro}, duration=10.0, threads=2)["hash"] == r["hash"]
    s = r["summary"]
    assert s["geometry_bound"]["elements"] == 12 and s["geometry_bound"]["evaluations"] == 0
    assert s["faults"] == []
    assert 0.05 < s["peaks"]["head_ux"]["abs"] < 1.0  # m: the head's sway


def test_run_summary_of_a_yielding_frame(el_centro):
    model = ntnrt.load(os.path.join(CONFIG, "portal_plastic.toml"))
    r = model.run(inputs={"ag_x": el_centro})
    assert r["hash"] == cli_hash([NTN_RUN, os.path.join(CONFIG, "portal_plastic.toml"),
                                  "--input", "ag_x=" + EL_CENTRO])
    s = r["summary"]
    assert s["plastic_directions"] > 0 and len(s["yielded"]) > 0
    assert all(y["level"] >= 1 for y in s["yielded"])
    e = s["energy_J"]
    assert e["hysteretic"] > 0
    # The work-energy identity of the scheme: the residual is rounding next to the input, and the
    # books by mechanism add up to the external work.
    assert abs(e["residual"]) < 1e-6 * max(abs(e["external"]), 1.0)
    accounts = ("kinetic_change", "elastic", "viscous", "hysteretic", "friction", "impacts",
                "fracture")
    assert abs(e["external"] - sum(e[k] for k in accounts) - e["residual"]) <= \
        1e-12 * abs(e["external"])
    assert e["friction"] == 0 and e["impacts"] == 0 and e["fracture"] == 0
    # Peaks are the largest |value| of every step, so at least every frame's.
    for name, p in s["peaks"].items():
        assert p["abs"] >= np.max(np.abs(r["outputs"][name]))


# A p_delta bar pulled past the stable step's bound of second-order geometry at 0.114 s (frame 113;
# tests/tools/past_geometry_bound.toml).
PAST_BOUND = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools",
                          "past_geometry_bound.toml")


def test_run_summary_geometry_bound_and_faults(tmp_path):
    # The bound and the fault bits in the summary, as ntn-run's JSON has them: past the bound from
    # its frame on (a run to 0.2 s), inside it (to 0.1 s); a model without second-order geometry.
    model = ntnrt.load(PAST_BOUND)
    for seconds, past in ((0.2, True), (0.1, False)):
        s = model.run(inputs={}, duration=seconds)["summary"]
        out = str(tmp_path / f"summary_{seconds}.json")
        subprocess.run([NTN_RUN, PAST_BOUND, "--duration", str(seconds), "--summary-json", out,
                        "-q"], check=True, capture_output=True)
        with open(out) as f:
            cli = json.load(f)
        bound = s["geometry_bound"]
        assert {k: bound[k] for k in ("elements", "evaluations", "first_frame")} == \
            {k: cli["geometry_bound"][k] for k in ("elements", "evaluations", "first_frame")}
        assert s["faults"] == cli["faults"]
        assert bound["elements"] == 1
        if past:
            assert 110 <= bound["first_frame"] <= 116  # the pull reaches Q_max at 0.1138 s
            assert bound["evaluations"] > 0
            assert bound["first_time_s"] == pytest.approx(cli["geometry_bound"]["first_time_s"],
                                                          rel=1e-8)
            assert s["faults"] == ["geometry_bound"]
        else:
            assert bound["evaluations"] == 0 and bound["first_frame"] == -1
            assert bound["first_time_s"] is None and cli["geometry_bound"]["first_time_s"] is None
            assert s["faults"] == []
    linear = ntnrt.load(os.path.join(CONFIG, "cantilever.toml")).run(inputs={}, duration=0.01)
    assert linear["summary"]["geometry_bound"] == {"elements": 0, "evaluations": 0,
                                                  "first_frame": -1, "first_time_s": None}
    assert linear["summary"]["faults"] == []


ENERGY_CHANNELS = ("external", "kinetic", "elastic", "viscous", "hysteretic", "friction",
                   "impacts", "fracture", "residual")


def test_energy_channels_every_frame(el_centro, tmp_path):
    # The books as channels: every frame's accounts, the last frame's the summary's (the same
    # state: bit for bit), each frame's closing (external = the others + residual, the residual
    # rounding), and ntn-run --energy writes the same values as CSV columns, without changing
    # the output hash.
    path = os.path.join(CONFIG, "portal_plastic.toml")
    model = ntnrt.load(path)
    r = model.run(inputs={"ag_x": el_centro}, duration=10.0)
    e = r["energy"]
    assert tuple(e.keys()) == ENERGY_CHANNELS
    assert all(len(e[k]) == len(r["time"]) for k in ENERGY_CHANNELS)
    end = r["summary"]["energy_J"]
    assert e["external"][-1] == end["external"] and e["kinetic"][-1] == end["kinetic_change"]
    assert e["hysteretic"][-1] == end["hysteretic"] and e["residual"][-1] == end["residual"]
    scale = np.maximum.accumulate(np.abs(e["external"]))
    assert np.all(np.abs(e["residual"]) <= 1e-10 * np.maximum(scale, 1.0))
    others = sum(e[k] for k in ENERGY_CHANNELS[1:-1])
    assert np.all(np.abs(e["external"] - others - e["residual"]) <= 1e-12 * np.maximum(scale, 1.0))
    assert e["hysteretic"][-1] > 0 and e["viscous"][-1] > 0
    csv = str(tmp_path / "energy.csv")
    args = [NTN_RUN, path, "--input", "ag_x=" + EL_CENTRO, "--duration", "10"]
    with_energy = cli_hash(args + ["--energy", "--out", csv])
    assert with_energy == cli_hash(args) == r["hash"]
    with open(csv) as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    names = ["energy_" + k + "[J]" for k in ENERGY_CHANNELS]
    assert header[-len(names):] == names
    for c, k in enumerate(ENERGY_CHANNELS):
        assert np.array_equal(table[:, len(header) - len(names) + c], e[k]), k


def test_modes_against_the_cantilever_closed_form():
    model = ntnrt.load(os.path.join(CONFIG, "cantilever.toml"))
    m = model.modes(6)
    E, rho, A, L = 210e9, 7850.0, 5.0e-3, 2.0
    Iy, Iz = 4.1666666666666666e-6, 1.0416666666666666e-6
    beta1 = 1.8751040687119611  # cos(x) cosh(x) = -1, first root
    f = lambda I: beta1**2 / (2 * math.pi * L**2) * math.sqrt(E * I / (rho * A))
    # Modes 1 and 2: the first bending mode about the weak axis (Iz, in x-y) and the strong axis
    # (Iy, in x-z). 0.5 %: the 20-element lumped-mass model is -0.13 % off the continuum
    # (tests/modal/modal_cantilever_test.cpp derives it).
    assert m["frequency"][0] == pytest.approx(f(Iz), rel=5e-3)
    assert m["frequency"][1] == pytest.approx(f(Iy), rel=5e-3)
    assert m["frequency"][0] < f(Iz) and m["frequency"][1] < f(Iy)  # lumped mass: lower
    # Effective mass of a uniform cantilever's first mode: (int phi dx)^2 / (L int phi^2 dx) of
    # the exact shape phi = cosh - cos - sigma (sinh - sin) = 0.61307 of its mass. 0.5 %: the
    # lumped-mass discretization, of the order of the frequency's (0.13 %).
    total = rho * A * L
    assert m["effective_mass"][0, 1] / total == pytest.approx(0.61307, rel=5e-3)
    assert m["shapes"].shape == (6 * model.sizes["nodes"], 6)


def test_state_and_restore_are_bit_identical(frame3d, el_centro):
    values = el_centro.values

    def inputs(k):  # step k's input: the record's sample at k dt, held (0.02 s samples), in g
        return [values[min(int(k * frame3d.dt / el_centro.dt), values.size - 1)]]

    frame3d.reset()
    for k in range(600):
        frame3d.step(inputs(k))
    saved = frame3d.state()
    first = np.array([frame3d.step(inputs(600 + k)) for k in range(400)])
    frame3d.restore(saved)
    again = np.array([frame3d.step(inputs(600 + k)) for k in range(400)])
    assert first.tobytes() == again.tobytes()
    assert frame3d.tick == 1000


def test_bad_inputs_raise_and_leave_the_model_usable(frame3d, el_centro):
    nan = el_centro.values.copy()
    nan[100] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        frame3d.run(inputs={"ag_x": (nan, el_centro.dt, "g")})
    with pytest.raises(ValueError, match="no input channel 'ag_y'.*ag_x"):
        frame3d.run(inputs={"ag_y": el_centro})
    with pytest.raises(ValueError, match="no record for input channel 'ag_x'"):
        frame3d.run(inputs={})
    with pytest.raises(ValueError, match="outside the input's range"):
        frame3d.run(inputs={"ag_x": (el_centro.values * 1e3, el_centro.dt, "g")})
    with pytest.raises(ValueError, match="unit"):
        frame3d.run(inputs={"ag_x": (el_centro.values, el_centro.dt, "N")})
    frame3d.reset()
    with pytest.raises(ValueError, match="1 input channels; got 2"):
        frame3d.step([0.0, 0.0])
    with pytest.raises(ValueError, match="not finite"):
        frame3d.step([float("inf")])
    assert frame3d.tick == 0  # nothing reached the state
    assert frame3d.run(inputs={"ag_x": el_centro})["hash"] == FRAME3D_EL_CENTRO


def test_run_scale_multiplies_the_records(frame3d, el_centro, tmp_path):
    # frame3d is linear (no gravity, no loads, at rest at t = 0): a factor 2 scales every
    # intermediate result of its steps exactly (tests/tools/scale_test.cpp says why), so every
    # output is exactly twice the unscaled one, and a factor 1/2 undoes a model file's 2 to the bit.
    def run(model, **scale):
        return model.run(inputs={"ag_x": el_centro}, duration=2.0, **scale)

    base = run(frame3d)
    two = run(frame3d, scale={"ag_x": 2})
    for name in frame3d.outputs:
        assert np.array_equal(two["outputs"][name], 2 * base["outputs"][name]), name
    # The same run as the command line's FILE*2.
    frame3d_toml = os.path.join(CONFIG, "frame3d.toml")
    assert two["hash"] == cli_hash([NTN_RUN, frame3d_toml, "--input", "ag_x=" + EL_CENTRO + "*2",
                                    "--duration", "2"])
    # The model file's scale and this one multiply.
    text = open(frame3d_toml).read()
    assert 'units = "g"\n' in text
    scaled = tmp_path / "frame3d_scale2.toml"
    scaled.write_text(text.replace('units = "g"\n', 'units = "g"\nscale = 2.0\n', 1))
    file2 = ntnrt.load(str(scaled))
    assert run(file2, scale={"ag_x": 0.5})["hash"] == base["hash"]
    four = run(file2, scale={"ag_x": 2.0})
    for name in frame3d.outputs:
        assert np.array_equal(four["outputs"][name], 4 * base["outputs"][name]), name


def test_bad_scale_factors_raise(frame3d, el_centro):
    for bad in [float("nan"), float("inf"), -float("inf"), 0.0]:
        with pytest.raises(ValueError, match="scale.'ag_x'.* finite number other than 0"):
            frame3d.run(inputs={"ag_x": el_centro}, scale={"ag_x": bad})
    with pytest.raises(ValueError, match="scale.'ag_x'.*a number"):
        frame3d.run(inputs={"ag_x": el_centro}, scale={"ag_x": "2"})
    with pytest.raises(ValueError, match="no input channel 'ag_y'"):
        frame3d.run(inputs={"ag_x": el_centro}, scale={"ag_y": 2.0})
    # A factor that takes the record out of the input's range ([-3, 3] g; El Centro's peak is
    # 0.319 g): the range is of the values the channel receives, the record scaled.
    with pytest.raises(ValueError, match="outside the input's range"):
        frame3d.run(inputs={"ag_x": el_centro}, scale={"ag_x": 10.0})
    assert frame3d.run(inputs={"ag_x": el_centro})["hash"] == FRAME3D_EL_CENTRO


def test_psd_keeps_the_variance():
    fs, f0 = 200.0, 5.0
    t = np.arange(40000) / fs
    rng = np.random.default_rng(1)
    x = np.sin(2 * np.pi * f0 * t) + 0.1 * rng.standard_normal(t.size)
    f, p = ntnrt.psd(x, fs, resolution=0.5)
    assert f[np.argmax(p)] == pytest.approx(f0, abs=0.5)
    # Parseval: the one-sided PSD integrates to the variance (the mean is removed); 3 %: the
    # Welch estimate of a 200-segment average.
    assert np.sum(p) * (f[1] - f[0]) == pytest.approx(np.var(x), rel=3e-2)
    with pytest.raises(ValueError):
        ntnrt.psd(np.array([1.0, np.nan] * 1000), fs, resolution=1.0)


def test_check_modes_equals_the_command_line(frame3d, el_centro, tmp_path):
    r = frame3d.run(inputs={"ag_x": el_centro})
    fs = 1.0 / frame3d.frame_period
    data = {name: r["outputs"][name] for name in frame3d.outputs}
    got = ntnrt.check_modes(frame3d, data, fs, modes=2, direction=0)
    csv = tmp_path / "frame3d.csv"
    subprocess.run([os.path.join(RUNNERS, "ntn-run-frame3d"), "--input", "ag_x=" + EL_CENTRO,
                    "--out", str(csv), "-q"], check=True, capture_output=True)
    cli = subprocess.run([CHECK_MODES, os.path.join(CONFIG, "frame3d.toml"), str(csv), "-n", "2",
                          "-d", "x", "--json", "-"], capture_output=True, text=True)
    want = json.loads(cli.stdout)
    assert got["pass"] == want["pass"] == (cli.returncode == 0)
    # The same spectrum to the bit: the same peaks (the JSON prints 10 significant digits).
    assert [float("%.10g" % m["identified_hz"]) for m in got["modes"]] == [
        m["identified_hz"] for m in want["modes"]]
    assert "mode" in got["table"]


def test_the_worked_example_runs(tmp_path):
    out = subprocess.run([sys.executable, EXAMPLE, "--out", str(tmp_path)], capture_output=True,
                         text=True, env=dict(os.environ))
    assert out.returncode == 0, out.stderr
    assert FRAME3D_EL_CENTRO in out.stdout
    try:
        import matplotlib  # noqa: F401 (python3-matplotlib: the example then draws its plot)
    except ImportError:
        return
    assert (tmp_path / "el_centro.png").stat().st_size > 10000
