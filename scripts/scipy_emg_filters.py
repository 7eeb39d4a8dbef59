#!/usr/bin/env python3
"""SciPy's own Butterworth filters, the reference that crates/core/src/emg/tests/scipy_reference.rs
compares the Rust filters (crates/core/src/emg/) against. Writes two tables to crates/core/tests/reference/emg/:

  - scipy_butter_sos.csv: `case,btype,order,low_hz,high_hz,fs_hz,section,b0,b1,b2,a0,a1,a2`, the
    second-order sections of `scipy.signal.butter(order, cut-off(s), btype, fs=fs_hz,
    output='sos')` for each case (high_hz is empty for a low- or high-pass, whose cut-off is
    low_hz);
  - scipy_filtered.csv: `index,input,<case>_causal,<case>_zero_phase,...`: one input signal and,
    for each case, `scipy.signal.sosfilt(sos, x)` (causal, zero initial state) and
    `scipy.signal.sosfiltfilt(sos, x)` (zero-phase: odd extension of the default length
    3 (2 n_sections + 1 - ...), steady-state initial conditions from sosfilt_zi).

Each file starts with a comment line naming the SciPy and NumPy versions and this command. Numbers
are in Python's shortest round-trip form (exact doubles), so the Rust test reads the very input
SciPy filtered. The input is seeded noise (NumPy's PCG64, seed 20030765) plus a DC offset and a
slow sine, so the filters meet an offset, a low frequency and broadband content.

Rerun (SciPy 1.17.1 and NumPy 2.4.6 wrote the committed tables; any venv will do):

    python3.11 -m venv /tmp/venv-scipy && /tmp/venv-scipy/bin/pip install scipy numpy
    /tmp/venv-scipy/bin/python scripts/scipy_emg_filters.py [--out-dir crates/core/tests/reference/emg]

The Rust test needs only the committed tables, not SciPy.
"""

import argparse
import math
from pathlib import Path

import numpy as np
import scipy
import scipy.signal as signal

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = 240
SEED = 20030765

# (name, btype, order, low_hz, high_hz or None, fs_hz): low-, high- and band-pass, even and odd
# orders, the EMG chain's defaults among them (20-450 Hz band, 6 Hz envelope).
CASES = [
    ("lp2", "lowpass", 2, 6.0, None, 1000.0),
    ("lp3", "lowpass", 3, 50.0, None, 1000.0),
    ("lp4", "lowpass", 4, 6.0, None, 1000.0),
    ("hp2", "highpass", 2, 20.0, None, 1000.0),
    ("hp5", "highpass", 5, 100.0, None, 1000.0),
    ("bp2", "bandpass", 2, 20.0, 450.0, 1000.0),
    ("bp3", "bandpass", 3, 30.0, 300.0, 1000.0),
    ("bp4", "bandpass", 4, 20.0, 450.0, 2000.0),
]


def number(x):
    """The shortest text that reads back as the same double."""
    return repr(float(x))


def design(btype, order, low_hz, high_hz, fs_hz):
    cut = low_hz if high_hz is None else [low_hz, high_hz]
    return signal.butter(order, cut, btype=btype, fs=fs_hz, output="sos")


def input_signal():
    rng = np.random.default_rng(SEED)
    t = np.arange(SAMPLES) / 1000.0
    return 0.3 + np.sin(2.0 * math.pi * 3.0 * t) + rng.standard_normal(SAMPLES)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out-dir", default=str(ROOT / "crates" / "core" / "tests" / "reference" / "emg"))
    args = parser.parse_args()
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    header = (
        f"# SciPy {scipy.__version__}, NumPy {np.__version__}; "
        "written by `python scripts/scipy_emg_filters.py`\n"
    )

    x = input_signal()
    columns = [("input", x)]
    sos_rows = []
    for name, btype, order, low, high, fs in CASES:
        sos = design(btype, order, low, high, fs)
        for k, section in enumerate(sos):
            fields = [name, btype, str(order), number(low), "" if high is None else number(high)]
            fields += [number(fs), str(k)] + [number(c) for c in section]
            sos_rows.append(",".join(fields))
        columns.append((f"{name}_causal", signal.sosfilt(sos, x)))
        columns.append((f"{name}_zero_phase", signal.sosfiltfilt(sos, x)))

    with open(out / "scipy_butter_sos.csv", "w") as f:
        f.write(header)
        f.write("case,btype,order,low_hz,high_hz,fs_hz,section,b0,b1,b2,a0,a1,a2\n")
        f.write("\n".join(sos_rows) + "\n")
    with open(out / "scipy_filtered.csv", "w") as f:
        f.write(header)
        f.write(",".join(["index"] + [c for c, _ in columns]) + "\n")
        for i in range(SAMPLES):
            f.write(",".join([str(i)] + [number(v[i]) for _, v in columns]) + "\n")


if __name__ == "__main__":
    main()
