#!/usr/bin/env python3
"""The OpenSim references of the muscle cross-validation (docs/validation.md "Against OpenSim"):
for every configuration `crates/core/tests/opensim/*.config.toml` (one muscle on a driven slider) and every
motion `crates/core/tests/opensim/*.scenario.toml`, the engine's run gives the inputs, the activation and the
path length after each tick, and OpenSim 4.6 simulates the same muscle on them
(scripts/opensim_muscle.py). Writes `crates/core/tests/reference/opensim/CONFIG__MOTION.csv`: a comment line
naming the OpenSim version, then `t,activation,mtu_length,tendon_force,fiber_length`, a row per
tick (OpenSim's tendon force and fibre length; the inputs as OpenSim read them back), numbers in
Python's shortest round-trip form.

    .venv/bin/python scripts/opensim_validation.py [--out DIR] [--only NAME...]

The engine side is the installed `muscle_actuator` package (`simulate`, the Hill model, the
configuration's default stepping). crates/core/tests/opensim_muscles.rs runs the same
configurations and motions and compares them with these files; python/tests/
test_opensim_muscles.py regenerates the files and requires them equal to the committed ones.

The activation OpenSim is given is the engine's after each tick, linear in between (the slow
time constants of the configurations keep that within 1e-4 of the engine's exponential within a
tick). On an elastic tendon it is at least 0.01: OpenSim's Thelen2003Muscle clamps its activation
there and its DeGrooteFregly2016Muscle divides by it, and the engine's equilibrium fibre without a
damper works with the same floor (docs/model.md §5b). The path length is the engine's after each
tick: within a tick the engine moves the driven slider linearly, so both sides follow the same
piecewise-linear path.
"""

import argparse
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np

import muscle_actuator as ma

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = os.path.join(ROOT, "crates", "core", "tests", "opensim")
OUT = os.path.join(ROOT, "crates", "core", "tests", "reference", "opensim")
ACTIVATION_FLOOR = 0.01
# The slider's geometry in every configuration: L = PATH - ARM * angle.
PATH, ARM = 0.3, 0.02


def muscle_of(config_path):
    """The muscle table of a configuration (tomllib: the standard library's reader)."""
    import tomllib

    with open(config_path, "rb") as f:
        return tomllib.load(f)["muscle"][0]


def cases(only):
    configs = sorted(glob.glob(os.path.join(CASES, "*.config.toml")))
    motions = sorted(glob.glob(os.path.join(CASES, "*.scenario.toml")))
    for c in configs:
        for m in motions:
            name = f"{os.path.basename(c)[:-len('.config.toml')]}__" \
                   f"{os.path.basename(m)[:-len('.scenario.toml')]}"
            if not only or name in only:
                yield name, c, m


def engine_inputs(config_path, scenario_path, tendon):
    run = ma.simulate(scenario_path, "hill", config_path)
    a = run["activation"][:, 0]
    if tendon == "elastic":
        a = np.maximum(a, ACTIVATION_FLOOR)
    length = PATH - ARM * run["joint.position"][:, 0]
    return run.time, a, length


def opensim(muscle, inputs_csv, out_csv):
    args = [
        sys.executable, os.path.join(ROOT, "scripts", "opensim_muscle.py"),
        "--inputs", inputs_csv, "--out", out_csv,
        "--muscle", muscle["curves"], "--tendon", muscle["tendon"],
        "--fmax", repr(muscle["f_max"]), "--lopt", repr(muscle["l_opt"]),
        "--lts", repr(muscle["l_ts"]), "--vmax", repr(muscle["v_max"]),
        "--pennation", repr(muscle["pennation"]),
    ]
    # The fibre damper b_m (N s/m) as OpenSim's fiber_damping, in Fmax per vmax.
    if muscle.get("b_m", 0.0) > 0.0:
        args += ["--damping", repr(muscle["b_m"] * muscle["v_max"] / muscle["f_max"])]
    # The curve sets' constants the configuration sets, under OpenSim's names.
    for key in ("tendon_strain", "passive_strain", "active_force_width_scale", "kshape_active",
                "kshape_passive", "af", "flen"):
        if key in muscle:
            args += ["--" + key.replace("_", "-"), repr(muscle[key])]
    subprocess.run(args, check=True, timeout=600)
    with open(out_csv) as f:
        lines = [ln.strip() for ln in f if ln.strip()]
    version = lines[0]
    header = lines[1].split(",")
    rows = [[float(x) for x in ln.split(",")] for ln in lines[2:]]
    return version, header, rows


def opensim_version():
    import opensim as osim

    return osim.GetVersion()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=OUT)
    ap.add_argument("--only", nargs="*", default=[])
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for name, config, scenario in cases(set(args.only)):
            muscle = muscle_of(config)
            t, a, length = engine_inputs(config, scenario, muscle["tendon"])
            inputs = os.path.join(tmp, "inputs.csv")
            with open(inputs, "w") as f:
                f.write("t,activation,mtu_length\n")
                for row in zip(t, a, length):
                    f.write(",".join(repr(float(x)) for x in row) + "\n")
            _, header, rows = opensim(muscle, inputs, os.path.join(tmp, "out.csv"))
            cols = [header.index(c) for c in
                    ("t", "activation", "mtu_length", "tendon_force", "fiber_length")]
            with open(os.path.join(args.out, f"{name}.csv"), "w") as f:
                f.write(f"# OpenSim {opensim_version()}: "
                        f"scripts/opensim_validation.py --only {name}\n")
                f.write("t,activation,mtu_length,tendon_force,fiber_length\n")
                for r in rows:
                    f.write(",".join(repr(r[c]) for c in cols) + "\n")
            print(f"{name}: {len(rows)} rows", file=sys.stderr)


if __name__ == "__main__":
    main()
