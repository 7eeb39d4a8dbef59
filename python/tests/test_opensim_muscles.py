"""OpenSim 4.6 itself, simulated now, against the muscle references the Rust tests read.

crates/core/tests/opensim_muscles.rs compares the engine's equilibrium Hill muscles (DeGroote-Fregly 2016,
Thelen 2003 and Millard 2012 curves, elastic and rigid tendons, pennation 0 and 0.2 rad) with
crates/core/tests/reference/opensim/*.csv; this test regenerates those files with the installed OpenSim
(scripts/opensim_validation.py: the installed engine's run gives the inputs, OpenSim simulates the
muscle on them) and requires them to be the committed ones: the inputs exactly, OpenSim's
outputs within what its integrator's accuracy moves them (1e-12 against 1e-14: 3e-6 N, 1e-10 m).
The Rust tests thus compare against OpenSim's numbers for the engine's inputs of today."""

import os
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REFERENCES = os.path.join(ROOT, "crates", "core", "tests", "reference", "opensim")


def read(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    assert lines[0].strip() == "t,activation,mtu_length,tendon_force,fiber_length"
    return np.array([[float(x) for x in line.split(",")] for line in lines[1:]])


def test_the_committed_muscle_references_are_what_opensim_computes(tmp_path):
    import opensim as osim

    assert osim.__version__.startswith("4.6"), osim.__version__
    subprocess.run(
        [sys.executable, os.path.join(ROOT, "scripts", "opensim_validation.py"),
         "--out", str(tmp_path)],
        check=True,
        timeout=900,
    )
    committed = sorted(f for f in os.listdir(REFERENCES) if f.endswith(".csv"))
    assert len(committed) == 39
    assert sorted(os.listdir(tmp_path)) == committed
    for name in committed:
        fresh, ref = read(tmp_path / name), read(os.path.join(REFERENCES, name))
        assert fresh.shape == ref.shape, name
        # Time and path length: the engine's, exactly; activation: OpenSim's read-back of it.
        assert np.array_equal(fresh[:, [0, 2]], ref[:, [0, 2]]), name
        assert np.max(np.abs(fresh[:, 1] - ref[:, 1])) <= 1e-12, name
        assert np.max(np.abs(fresh[:, 3] - ref[:, 3])) <= 1e-4, name
        assert np.max(np.abs(fresh[:, 4] - ref[:, 4])) <= 1e-10, name
