#!/usr/bin/env python3
"""OpenSim's own evaluation of the curve sets `degroote2016`, `thelen2003` and `millard2012`, the
reference that
crates/core/src/physics/curves/tests/opensim.rs compares the Rust curves (crates/core/src/physics/curves/)
against. Writes crates/core/tests/reference/opensim_curves.csv: a comment line naming the OpenSim version and
this command, then `set,curve,x,value`, one row per point, numbers in Python's shortest
round-trip form (exact doubles).

Needs OpenSim's Python package (PyPI `opensim` 4.6), which scripts/py-env.sh installs in .venv:

    .venv/bin/python scripts/opensim_curves.py [--out crates/core/tests/reference/opensim_curves.csv]

python/tests/test_opensim_curves.py runs it in the test command and requires the committed table.

DeGrooteFregly2016Muscle exposes its curves (`calc...` methods; the force-velocity pair is
static): they are called directly, on a default muscle after `finalizeFromProperties()` (which
computes the tendon's kT). Thelen2003Muscle does not expose its curves to Python, so they are read
from a one-muscle model (ground, a slider, the muscle between them; Fmax = 1 N, optimal fibre
length = tendon slack length = 1 m, no pennation, so normalised and absolute quantities are the
same numbers): the fibre-length state and the path length are set, the state realized to
Velocity (Dynamics for the tendon's stiffness, its curve's derivative), and the muscle's
multipliers read. Thelen's force-velocity relation runs backwards in
OpenSim: the muscle computes the multiplier from the force balance, `fv = (fse - fpe)/(a fal)`,
and the fibre velocity from it (`calcdlceN`); the rows are those pairs, (velocity, multiplier),
at activation 1 and at activation 0.5 (Thelen's maximum velocity scales with 0.25 + 0.75 a).
Every x written is the argument OpenSim evaluated (read back from the model), not the one asked
for.

Millard2012EquilibriumMuscle's curves are OpenSim components of their own (ActiveForceLengthCurve,
ForceVelocityCurve, FiberForceLengthCurve, TendonForceLengthCurve), each called directly with its
default properties: value, first derivative and (passive and tendon) integral, also past the
curves' ends, where they continue linearly.
"""

import argparse
import math
import os
import sys

import opensim as osim

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POINTS = 60


def linspace(a, b, n=POINTS):
    return [a + (b - a) * i / (n - 1) for i in range(n)]


def degroote_rows():
    m = osim.DeGrooteFregly2016Muscle()
    m.finalizeFromProperties()
    dgf = osim.DeGrooteFregly2016Muscle
    rows = []

    def add(curve, xs, f):
        rows.extend(("degroote2016", curve, x, f(x)) for x in xs)

    lengths = linspace(0.2, 1.8)
    add("active_force_length", lengths, m.calcActiveForceLengthMultiplier)
    add("active_force_length_derivative", lengths, m.calcActiveForceLengthMultiplierDerivative)
    add("passive_force_length", lengths, m.calcPassiveForceMultiplier)
    add("passive_force_length_derivative", lengths, m.calcPassiveForceMultiplierDerivative)
    add("force_velocity", linspace(-1.1, 1.1), dgf.calcForceVelocityMultiplier)
    add("force_velocity_inverse", linspace(0.0, 1.79), dgf.calcForceVelocityInverseCurve)
    tendon = linspace(0.95, 1.09)
    add("tendon_force_length", tendon, m.calcTendonForceMultiplier)
    add("tendon_force_length_derivative", tendon, m.calcTendonForceMultiplierDerivative)
    add("tendon_force_length_inverse", linspace(0.0, 5.0), m.calcTendonForceLengthInverseCurve)
    return rows


class ThelenModel:
    """One Thelen2003Muscle between ground and a slider: Fmax 1 N, lopt 1 m, tendon slack 1 m."""

    def __init__(self):
        model = osim.Model()
        body = osim.Body("slider_body", 1.0, osim.Vec3(0), osim.Inertia(1))
        model.addBody(body)
        joint = osim.SliderJoint("slider", model.getGround(), body)
        model.addJoint(joint)
        muscle = osim.Thelen2003Muscle("muscle", 1.0, 1.0, 1.0, 0.0)
        muscle.addNewPathPoint("origin", model.getGround(), osim.Vec3(0))
        muscle.addNewPathPoint("insertion", body, osim.Vec3(0))
        model.addForce(muscle)
        joint.updCoordinate().setDefaultValue(2.0)
        self.state = model.initSystem()
        self.model = model
        self.coord = joint.updCoordinate()
        self.muscle = osim.Thelen2003Muscle.safeDownCast(model.getForceSet().get("muscle"))

    def set(self, fibre_length, tendon_length, activation=1.0):
        """Set the state; the path length is fibre + tendon (no pennation)."""
        s = self.state
        self.coord.setValue(s, fibre_length + tendon_length)
        self.coord.setSpeedValue(s, 0.0)
        self.muscle.setActivation(s, activation)
        self.muscle.setFiberLength(s, fibre_length)
        self.model.realizeVelocity(s)
        return s


def thelen_fse(strain, e0=0.04):
    """Thelen2003Muscle::calcfse, here only to choose tendon strains for a wanted force."""
    t1 = math.exp(3.0)
    e_toe = 99.0 * e0 * t1 / (166.0 * t1 - 67.0)
    k_lin = 0.67 / (e0 - e_toe)
    if strain > e_toe:
        return k_lin * (strain - e_toe) + 0.33
    return 0.33 / (math.exp(3.0) - 1.0) * (math.exp(3.0 * strain / e_toe) - 1.0) if strain > 0 else 0.0


def solve(f, target, lo, hi):
    """Bisection for f(x) = target, f increasing on [lo, hi]."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def thelen_rows():
    tm = ThelenModel()
    mu = tm.muscle
    rows = []
    for lce in linspace(0.3, 1.8):
        s = tm.set(lce, 1.0)
        x = mu.getNormalizedFiberLength(s)
        rows.append(("thelen2003", "active_force_length", x, mu.getActiveForceLengthMultiplier(s)))
    for lce in linspace(0.9, 1.7):
        s = tm.set(lce, 1.0)
        x = mu.getNormalizedFiberLength(s)
        rows.append(("thelen2003", "passive_force_length", x, mu.getPassiveForceMultiplier(s)))
    for strain in linspace(-0.005, 0.06):
        s = tm.set(1.0, 1.0 + strain)
        tm.model.realizeDynamics(s)
        x = mu.getTendonLength(s)
        rows.append(("thelen2003", "tendon_force_length", x, mu.getTendonForce(s)))
        rows.append(("thelen2003", "tendon_force_length_derivative", x, mu.getTendonStiffness(s)))
    # Force-velocity: choose the multiplier, make the force balance give it, read the velocity.
    # fv >= 0: fibre at optimal length (fal = 1, fpe = 0), tendon force fse = fv.
    # fv < 0: tendon slack (fse = 0), fibre stretched so that -fpe/fal = fv.
    for activation, curve in ((1.0, "force_velocity"), (0.5, "force_velocity_half_activation")):
        for fv in linspace(-0.2, 1.6):
            if fv >= 0.0:
                lce, tendon = 1.0, 1.0 + solve(thelen_fse, fv * activation, 0.0, 0.5)
            else:
                lce = solve(lambda l: -thelen_balance(l) / activation, -fv, 1.0, 1.8)
                tendon = 0.99
            s = tm.set(lce, tendon, activation)
            v = mu.getNormalizedFiberVelocity(s)
            rows.append(("thelen2003", curve, v, mu.getForceVelocityMultiplier(s)))
    return rows


def thelen_balance(lce, e0=0.6, kpe=5.0, kshape=0.45):
    """-fpe/fal of Thelen2003Muscle at normalised fibre length lce, to choose fibre lengths."""
    fpe = (math.exp(kpe * (lce - 1.0) / e0) - 1.0) / (math.exp(kpe) - 1.0) if lce > 1.0 else 0.0
    fal = math.exp(-((lce - 1.0) ** 2) / kshape)
    return -fpe / fal


def millard_rows():
    active = osim.ActiveForceLengthCurve()
    fv = osim.ForceVelocityCurve()
    passive = osim.FiberForceLengthCurve()
    tendon = osim.TendonForceLengthCurve()
    rows = []

    def add(curve, xs, f):
        rows.extend(("millard2012", curve, x, f(x)) for x in xs)

    lengths = linspace(0.3, 1.95)
    add("active_force_length", lengths, active.calcValue)
    add("active_force_length_derivative", lengths, lambda x: active.calcDerivative(x, 1))
    passive_lengths = linspace(0.9, 1.9)
    add("passive_force_length", passive_lengths, passive.calcValue)
    add("passive_force_length_derivative", passive_lengths, lambda x: passive.calcDerivative(x, 1))
    add("passive_force_length_integral", passive_lengths, passive.calcIntegral)
    velocities = linspace(-1.1, 1.1)
    add("force_velocity", velocities, fv.calcValue)
    add("force_velocity_derivative", velocities, lambda x: fv.calcDerivative(x, 1))
    tendon_lengths = linspace(0.95, 1.09)
    add("tendon_force_length", tendon_lengths, tendon.calcValue)
    add("tendon_force_length_derivative", tendon_lengths, lambda x: tendon.calcDerivative(x, 1))
    add("tendon_force_length_integral", tendon_lengths, tendon.calcIntegral)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "crates", "core", "tests", "reference", "opensim_curves.csv"))
    args = ap.parse_args()
    osim.Logger.setLevelString("warn")
    rows = degroote_rows() + thelen_rows() + millard_rows()
    with open(args.out, "w") as f:
        f.write(f"# OpenSim {osim.GetVersionAndDate()} (PyPI opensim==4.6); written by "
                f"`.venv/bin/python scripts/opensim_curves.py`\n")
        f.write("set,curve,x,value\n")
        for set_name, curve, x, value in rows:
            f.write(f"{set_name},{curve},{x!r},{value!r}\n")
    print(f"{len(rows)} rows -> {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
