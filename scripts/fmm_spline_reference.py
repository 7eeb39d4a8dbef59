#!/usr/bin/env python3
"""Reference values of Forsythe, Malcolm & Moler's cubic spline (Computer Methods for
Mathematical Computations, 1977, the SPLINE routine), the interpolation CEINMS gives the curves
of its subject files (lib/Curve/Curve.cpp), for crates/core/src/physics/curves/tabulated/tests/.
Writes two tables to crates/core/tests/reference/tabulated/:

  - fmm_points.csv: `curve,index,x,y`, the points of each curve: the four curves of
    data/ceinms/uncalibratedSubject.xml (read from the file) and five made-up ones (two, three,
    four and seven points, the last two on one cubic, and nine seeded random points);
  - fmm_values.csv: `curve,x,value,slope,second,integral` at every point and at seven evenly
    spaced places inside every interval: the spline, its first and second derivatives, and its
    integral from the first point.

Three independent pieces of software make them:

  - R's `splinefun(x, y, method = "fmm")` (R's stats package, splines.c, the same algorithm
    as CEINMS) gives the value and the two derivatives (`deriv = 0, 1, 2`) and the cubic
    coefficients of each interval;
  - SciPy's `PPoly` built from those coefficients gives the integral (`PPoly.integrate`);
  - SciPy's `make_interp_spline(x, y, k=3)` with the FMM end conditions (the third derivative at
    each end that of the cubic through the four nearest points, none through three points)
    solves the spline again by B-spline collocation; the largest difference from R, relative
    to the largest |y| of the curve, is printed in each file's comment line and must stay below
    1e-9 (collocation is less accurate than FMM's elimination on the tendon curve, whose
    intervals range from 0.0005 to 10.8).

Numbers are in Python's shortest round-trip form (R's in `%.17g`), so the Rust test reads the
very doubles R evaluated at. Each file starts with a comment line naming the versions.

Rerun (R 4.2.2, SciPy 1.17.1 and NumPy 2.4.6 wrote the committed tables):

    apt-get install --no-install-recommends r-base-core
    python3.11 -m venv /tmp/venv-sp && /tmp/venv-sp/bin/pip install scipy numpy
    /tmp/venv-sp/bin/python scripts/fmm_spline_reference.py [--out-dir crates/core/tests/reference/tabulated]

The Rust test needs only the committed tables, not R or SciPy.
"""

import argparse
import subprocess
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import scipy
from scipy.interpolate import PPoly, make_interp_spline

ROOT = Path(__file__).resolve().parent.parent
SUBJECT = ROOT / "data" / "ceinms" / "uncalibratedSubject.xml"
SUBJECT_CURVES = ["activeForceLength", "passiveForceLength", "forceVelocity", "tendonForceStrain"]
# Places inside each interval, as fractions of its width.
INSIDE = [k / 8.0 for k in range(1, 8)]
SEED = 20250907
# Largest accepted difference between R and SciPy's collocation, relative to max |y|.
AGREEMENT = 1e-9

R_SCRIPT = r"""
args <- commandArgs(trailingOnly = TRUE)
p <- read.csv(args[1])
q <- read.csv(args[2])
f <- splinefun(p$x, p$y, method = "fmm")
z <- environment(f)$z
g <- function(v) sprintf("%.17g", v)
write.csv(data.frame(x = g(q$x), value = g(f(q$x, deriv = 0)), slope = g(f(q$x, deriv = 1)),
                     second = g(f(q$x, deriv = 2))), args[3], row.names = FALSE, quote = FALSE)
write.csv(data.frame(b = g(z$b), c = g(z$c), d = g(z$d)), args[4], row.names = FALSE,
          quote = FALSE)
"""


def number(v):
    """The shortest text that reads back as the same double."""
    return repr(float(v))


def subject_curves():
    """The four curves of the subject file, by name, as (x, y) lists."""
    root = ET.parse(SUBJECT).getroot()
    found = {}
    for curve in root.find("mtuDefault").findall("curve"):
        x = [float(v) for v in curve.find("xPoints").text.split()]
        y = [float(v) for v in curve.find("yPoints").text.split()]
        found[curve.find("name").text.strip()] = (x, y)
    return [(name, *found[name]) for name in SUBJECT_CURVES]


def made_up_curves():
    """Curves of two and three points (a line, a parabola), points on one cubic (four and
    seven, unevenly spaced) and nine seeded random points."""
    cubic = lambda v: 0.5 - 1.25 * v + 0.75 * v**2 + 0.4 * v**3
    x4 = [-1.0, -0.2, 0.5, 2.0]
    x7 = [-2.0, -1.3, -0.4, 0.1, 0.35, 1.6, 2.2]
    rng = np.random.default_rng(SEED)
    x9 = np.cumsum(rng.uniform(0.05, 1.5, 9)).tolist()
    y9 = rng.uniform(-1.0, 2.0, 9).tolist()
    return [
        ("line2", [0.5, 2.0], [1.0, -0.5]),
        ("parabola3", [0.0, 0.3, 1.0], [1.0, 2.0, 0.5]),
        ("cubic4", x4, [cubic(v) for v in x4]),
        ("cubic7", x7, [cubic(v) for v in x7]),
        ("random9", x9, y9),
    ]


def places(x):
    """Every point and seven places inside each interval."""
    out = []
    for i in range(len(x) - 1):
        out.append(x[i])
        out += [x[i] + t * (x[i + 1] - x[i]) for t in INSIDE]
    out.append(x[-1])
    return out


def third_divided_difference(x, y):
    f1 = [(y[i + 1] - y[i]) / (x[i + 1] - x[i]) for i in range(3)]
    f2 = [(f1[i + 1] - f1[i]) / (x[i + 2] - x[i]) for i in range(2)]
    return (f2[1] - f2[0]) / (x[3] - x[0])


def collocation(x, y):
    """SciPy's B-spline interpolant with FMM's end conditions."""
    if len(x) < 4:
        ends = (0.0, 0.0)
    else:
        ends = (6.0 * third_divided_difference(x[:4], y[:4]),
                6.0 * third_divided_difference(x[-4:], y[-4:]))
    if len(x) == 2:
        return lambda q: np.interp(q, x, y)
    return make_interp_spline(x, y, k=3, bc_type=([(3, ends[0])], [(3, ends[1])]))


def run_r(x, y, q, work):
    """R's FMM spline at q: (value, slope, second) columns and the (b, c, d) coefficients."""
    pts, at, out, coef, script = (work / n for n in ("p.csv", "q.csv", "o.csv", "c.csv", "s.R"))
    pts.write_text("x,y\n" + "".join(f"{number(a)},{number(b)}\n" for a, b in zip(x, y)))
    at.write_text("x\n" + "".join(f"{number(v)}\n" for v in q))
    script.write_text(R_SCRIPT)
    subprocess.run(["Rscript", str(script), str(pts), str(at), str(out), str(coef)], check=True)
    values = np.loadtxt(out, delimiter=",", skiprows=1)[:, 1:]
    b, c, d = np.loadtxt(coef, delimiter=",", skiprows=1, unpack=True)
    return values, (b, c, d)


def integrals(x, y, coefficients, q):
    """∫ from x[0] to each q of the piecewise cubic with R's coefficients, by SciPy's PPoly."""
    b, c, d = coefficients
    n = len(x) - 1
    poly = PPoly(np.array([d[:n], c[:n], b[:n], np.array(y[:n])]), np.array(x))
    return [poly.integrate(x[0], v) for v in q]


def r_version():
    out = subprocess.run(["Rscript", "-e", "cat(R.version.string)"], check=True,
                         capture_output=True, text=True)
    return out.stdout.split(" (")[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out-dir", default=str(ROOT / "crates" / "core" / "tests" / "reference" / "tabulated"))
    args = parser.parse_args()
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    point_rows, value_rows, agreement = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for name, x, y in subject_curves() + made_up_curves():
            point_rows += [f"{name},{i},{number(a)},{number(b)}" for i, (a, b) in enumerate(zip(x, y))]
            q = places(x)
            values, coefficients = run_r(x, y, q, Path(tmp))
            ints = integrals(x, y, coefficients, q)
            scale = max(abs(v) for v in y)
            gap = float(np.max(np.abs(collocation(x, y)(np.array(q)) - values[:, 0]))) / scale
            assert gap < AGREEMENT, f"{name}: R and SciPy differ by {gap:.3g} of max |y|"
            agreement.append(f"{name} {gap:.1e}")
            for v, row, integral in zip(q, values, ints):
                fields = [name, number(v)] + [number(w) for w in row] + [number(integral)]
                value_rows.append(",".join(fields))
    header = (
        f"# {r_version()} (splinefun, method fmm), SciPy {scipy.__version__}, NumPy "
        f"{np.__version__}; R vs SciPy collocation, relative to max |y|: {', '.join(agreement)}; "
        "written by `python scripts/fmm_spline_reference.py`\n"
    )
    with open(out / "fmm_points.csv", "w") as f:
        f.write(header + "curve,index,x,y\n" + "\n".join(point_rows) + "\n")
    with open(out / "fmm_values.csv", "w") as f:
        f.write(header + "curve,x,value,slope,second,integral\n" + "\n".join(value_rows) + "\n")


if __name__ == "__main__":
    main()
