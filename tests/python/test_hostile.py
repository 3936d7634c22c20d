# The Python module against hostile but honest use: threads sharing one Model, values outside an
# input's range, states of another model, arrays of the wrong kind, NUL in paths, arguments of
# the wrong type. Each raises TypeError or ValueError (RuntimeError for a busy model) naming the
# argument, and nothing returns a wrong result.
import os
import threading

import numpy as np
import pytest

import ntnrt

CONFIG = os.environ["NTN_CONFIG_DIR"]
FRAME3D = os.path.join(CONFIG, "frame3d.toml")
EL_CENTRO = os.path.join(CONFIG, "ground-motions", "elCentro.AT2")


@pytest.fixture(scope="module")
def el_centro():
    return ntnrt.read_at2(EL_CENTRO)


def test_threads_sharing_a_model_get_the_right_result_or_busy(el_centro):
    # Each of 4 threads runs the same Model: every run that returns has the hash of a run alone;
    # the others raise "the model is busy" (a Model is one run's).
    model = ntnrt.load(FRAME3D)
    alone = model.run(inputs={"ag_x": el_centro}, duration=20.0)["hash"]
    hashes, busy, other = [], [], []
    start = threading.Barrier(4)

    def one():
        start.wait()
        try:
            hashes.append(model.run(inputs={"ag_x": el_centro}, duration=20.0)["hash"])
        except RuntimeError as e:
            (busy if "busy" in str(e) else other).append(str(e))

    threads = [threading.Thread(target=one) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert other == []
    assert len(hashes) >= 1 and len(hashes) + len(busy) == 4
    assert all(h == alone for h in hashes)
    # A step() while another thread runs is refused likewise; after the runs the model is free.
    assert model.step([0.0]).shape == (len(model.outputs),)


def test_step_refuses_an_input_outside_its_range_as_run_does(el_centro):
    model = ntnrt.load(FRAME3D)  # ag_x accepts [-3, 3] g
    with pytest.raises(ValueError, match=r"input 'ag_x' = 100 is outside its range \[-3, 3\]"):
        model.step([100.0])
    with pytest.raises(ValueError, match="outside its range"):
        model.step({"ag_x": -3.5})
    assert model.tick == 0  # nothing reached the model
    model.step([3.0])
    assert model.tick == 1


def test_step_says_what_it_wants():
    model = ntnrt.load(FRAME3D)
    with pytest.raises(TypeError, match="inputs: give 1 numbers"):
        model.step(None)
    with pytest.raises(ValueError, match="2 dimensions"):
        model.step(np.zeros((1, 1)))
    with pytest.raises(TypeError, match="dtype"):
        model.step(np.array(["a"]))
    with pytest.raises(TypeError, match=r"inputs\['ag_x'\]: give a number"):
        model.step({"ag_x": "1"})


def test_modes_needs_at_least_one():
    model = ntnrt.load(FRAME3D)
    for n in (0, -1):
        with pytest.raises(ValueError, match="at least 1"):
            model.modes(n)
    assert len(model.modes(2)["frequency"]) == 2


def test_a_state_restores_only_into_its_own_model():
    a, b = ntnrt.load(FRAME3D), ntnrt.load(FRAME3D)
    a.step([0.5])
    s = a.state()
    with pytest.raises(ValueError, match="another model"):
        b.restore(s)
    a.reset()
    a.restore(s)
    assert a.tick == 1


def test_records_take_real_values_at_a_record_files_rate():
    with pytest.raises(ValueError, match="at least one value"):
        ntnrt.Record(np.array([]), 0.01)
    for dt in (1e-7, 2.0, float("nan"), 0.0):
        with pytest.raises(ValueError, match=r"dt: the sample interval must be in \[1e-06, 1\] s"):
            ntnrt.Record(np.zeros(3), dt)
    for values in (np.array([1 + 2j]), np.array(["1.0"]), np.array([True, False]),
                   np.array([None], dtype=object)):
        with pytest.raises(TypeError, match="values: give"):
            ntnrt.Record(values, 0.01)
    with pytest.raises(ValueError, match="one-dimensional"):
        ntnrt.Record(np.zeros((2, 2)), 0.01)
    assert len(ntnrt.Record(np.arange(3), 0.01)) == 3  # integers are numbers


def test_paths_with_nul_are_refused():
    with pytest.raises(ValueError, match="NUL"):
        ntnrt.load(FRAME3D + "\x00junk")
    with pytest.raises(ValueError, match="NUL"):
        ntnrt.read_at2(EL_CENTRO + "\x00junk")


def test_run_arguments_of_the_wrong_type(el_centro):
    model = ntnrt.load(FRAME3D)
    with pytest.raises(TypeError, match="duration: give a number of seconds, got str"):
        model.run(inputs={"ag_x": el_centro}, duration="10")
    with pytest.raises(ValueError, match=r"duration: 1e\+20 s gives"):
        model.run(inputs={"ag_x": el_centro}, duration=1e20)


def test_run_prints_a_value_outside_the_range_in_six_digits():
    model = ntnrt.load(FRAME3D)
    huge = ntnrt.Record(np.array([0.0, 1e300, 0.0]), 0.01)
    with pytest.raises(ValueError, match=r"sample 1 = 1e\+300 g is outside") as e:
        model.run(inputs={"ag_x": huge})
    assert len(str(e.value)) < 200


def test_check_modes_names_its_arguments_as_python_takes_them():
    model = ntnrt.load(FRAME3D)
    t = np.arange(4096) / 100.0
    data = {"u": np.sin(2 * np.pi * 1.6 * t)}
    for kwargs, words in [
        ({"tolerance": float("nan")}, r"^tolerance is nan: it must be above 0 and at most 1$"),
        ({"tolerance": 1.5}, r"^tolerance is 1\.5: it must be above 0 and at most 1$"),
        ({"band": 0.0}, r"^band is 0: it must be above 0 and at most 1$"),
        ({"min_mac": -1.0}, r"^min_mac is -1: it must be in \[0, 1\]$"),
        ({"resolution": -1.0}, r"^resolution is -1 Hz: .*or 0: automatic$"),
        ({"modes": 0}, r"^modes is 0: it must be at least 1$"),
        ({"direction": 5}, r"^direction is 5: "),
    ]:
        with pytest.raises(ValueError, match=words):
            ntnrt.check_modes(model, data, 100.0, **kwargs)
