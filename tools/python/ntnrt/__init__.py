"""ntn-rt from Python: load a model file, run it on records, step it, check its modes.

    import ntnrt
    model = ntnrt.load("config/frame3d.toml")          # ntnrt.ModelError: file:line:column
    result = model.run(inputs={"ag_x": ntnrt.read_at2("config/ground-motions/elCentro.AT2")})
    result["hash"]                                     # ntn-run's output hash, bit for bit

The loop runs in C++ (the command-line tools' own code); tools/python/README.md lists the API.
"""

from ._ntnrt import (
    Model,
    ModelError,
    Record,
    State,
    check_modes,
    element_pass_target,
    load,
    psd,
    read_at2,
    read_record,
)

__all__ = [
    "Model",
    "ModelError",
    "Record",
    "State",
    "check_modes",
    "element_pass_target",
    "load",
    "psd",
    "read_at2",
    "read_record",
]
