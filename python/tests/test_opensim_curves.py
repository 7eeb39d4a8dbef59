"""OpenSim 4.6 itself, evaluated now, against the curve table the Rust tests read.

crates/core/src/physics/curves/tests/opensim.rs checks the project's DeGroote-Fregly 2016 and Thelen 2003
curves (crates/core/src/physics/curves/) against crates/core/tests/reference/opensim_curves.csv; this test
regenerates that table with the installed OpenSim (scripts/opensim_curves.py) and requires it to
be the committed one, value for value: the Rust tests compare against OpenSim's numbers, not
against a copy that could drift from them."""

import csv
import os
import subprocess
import sys


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TABLE = os.path.join(ROOT, "crates", "core", "tests", "reference", "opensim_curves.csv")



def rows(path):
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    return [(r["set"], r["curve"], float(r["x"]), float(r["value"])) for r in csv.DictReader(lines)]


def test_the_committed_curve_table_is_what_opensim_computes(tmp_path):
    import opensim as osim

    assert osim.__version__.startswith("4.6"), osim.__version__
    out = tmp_path / "curves.csv"
    subprocess.run(
        [sys.executable, os.path.join(ROOT, "scripts", "opensim_curves.py"), "--out", str(out)],
        check=True,
        timeout=300,
    )
    fresh, committed = rows(out), rows(TABLE)
    assert len(fresh) == len(committed) >= 1500
    sets = {r[0] for r in committed}
    assert sets == {"degroote2016", "thelen2003", "millard2012"}
    for a, b in zip(fresh, committed):
        assert a[:2] == b[:2]
        assert a[2] == b[2], (a, b)
        assert a[3] == b[3], (a, b)
