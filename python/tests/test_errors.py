"""Bad input from Python is a ValueError (a `ma.Error`, test_exceptions.py says of which kind) with
the command line's message, and changes nothing; a failed tick is a StepError naming the tick; no
shape, dtype or value crashes the interpreter."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import assert_bits_equal


def cli_error(cli, *args: str) -> str:
    p = cli(*args, check=False)
    assert p.returncode != 0
    line = [l for l in p.stderr.splitlines() if l.startswith("error: ")][0]
    return line[len("error: "):]


def test_unknown_model_config_and_scenario_carry_the_cli_message(cli, tmp_path):
    with pytest.raises(ValueError) as e:
        ma.Actuator("elbow", "hux")
    assert str(e.value) == cli_error(cli, "simulate", "pulse", "--model", "hux")
    with pytest.raises(ValueError) as e:
        ma.simulate("pulse", config="no-such-config.toml")
    assert str(e.value) == cli_error(cli, "simulate", "pulse", "--config", "no-such-config.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text('[[muscle]]\nname = "flexor"\nk_tt = 1.0\n')
    with pytest.raises(ValueError) as e:
        ma.Actuator(bad)
    assert str(e.value) == cli_error(cli, "simulate", "pulse", "--config", str(bad))
    with pytest.raises(ValueError) as e:
        ma.simulate("no-such-scenario")
    assert str(e.value) == cli_error(cli, "simulate", "no-such-scenario")
    with pytest.raises(ValueError) as e:
        ma.simulate("pulse", energy_model="kleiber")
    assert str(e.value) == cli_error(cli, "simulate", "pulse", "--energy-model", "kleiber")


def test_configuration_dicts_and_overrides_are_checked_as_files():
    with pytest.raises(ValueError, match=r"configuration dict: .*k_tt"):
        ma.Actuator({"muscle": [{"name": "flexor", "k_tt": 1.0}]})
    with pytest.raises(ValueError, match=r'no muscle named "biceps"'):
        ma.Actuator(overrides={"muscle.biceps.k_t": 1.0})
    with pytest.raises(ValueError, match="k_t"):
        ma.Actuator(overrides={"muscle.flexor.k_t": -5.0})
    with pytest.raises(ValueError, match="overrides has 1 entries"):
        ma.rollout("elbow", "hill", np.zeros((2, 3, 2)), overrides=[{}])
    with pytest.raises(ValueError, match=r"instance 1: .*no muscle named"):
        ma.rollout("elbow", "hill", np.zeros((2, 3, 2)), overrides=[{}, {"muscle.x.k_t": 1.0}])


def test_bad_inputs_are_refused_whole_and_change_nothing():
    a = ma.Actuator("elbow", "hill")
    a.step(excitation=[0.3, 0.3], ticks=5)
    before = a.get_state()
    cases = [
        (dict(excitation=[0.1, 0.2, 0.3]), r"excitation has shape \[3\]: expected \[2\] \(muscles\)"),
        (dict(excitation=[0.1, float("nan")]), r"excitation\[1\] = NaN is not finite"),
        (dict(excitation={"biceps": 1.0}), r'excitation: unknown name "biceps"'),
        (dict(excitation={"flexor": float("inf")}), r"must be finite"),
        (dict(excitation=[1.0, 0.0], external_torque=[np.inf]), r"external_torque\[0\] = inf is not finite"),
        (dict(excitation="high"), r"excitation must be an array of numbers"),
        (dict(ticks=-1), r"ticks = -1 must be >= 0"),
    ]
    for kwargs, msg in cases:
        with pytest.raises(ValueError, match=msg):
            a.step(**kwargs)
    assert a.tick == 5
    after = a.get_state()
    # nothing moved: the same next ticks
    x, y = ma.Actuator("elbow", "hill"), ma.Actuator("elbow", "hill")
    x.set_state(before)
    y.set_state(after)
    assert_bits_equal(x.rollout(np.ones((20, 2)))["force"], y.rollout(np.ones((20, 2)))["force"], "unchanged")
    with pytest.raises(ValueError, match=r"unknown output \"forces\""):
        a.rollout(np.zeros((3, 2)), outputs=["forces"])
    with pytest.raises(ValueError, match=r"excitation has shape \[3, 3\]: expected \[any, 2\]"):
        a.rollout(np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"rate_hz"):
        ma.Actuator(rate_hz=0.0)
    with pytest.raises(ValueError, match=r"substeps = -1 must be >= 1"):
        ma.Actuator(substeps=-1)
    with pytest.raises(ValueError, match=r"threads = -2 must be >= 1"):
        ma.rollout("elbow", "hill", np.zeros((1, 2, 2)), threads=-2)
    with pytest.raises(ValueError, match=r"threads = 0"):
        ma.rollout("elbow", "hill", np.zeros((1, 2, 2)), threads=0)
    with pytest.raises(ValueError, match="given twice"):
        ma.rollout([a, a], excitation=np.zeros((2, 2, 2)))


def test_a_failed_tick_raises_with_the_tick_and_leaves_the_last_good_state():
    # A tendon whose stiffness jumps makes the implicit solve fail under a hard pull.
    a = ma.Actuator("elbow", "hill", substeps=1, overrides={"muscle.*.k_t": 1e12, "joint.elbow.inertia": 1e-9})
    good = None
    with pytest.raises(ma.StepError) as e:
        for _ in range(2000):
            good = a.get_state()
            a.step(excitation=[1.0, 0.0], external_torque=[1e6])
    err = e.value
    assert isinstance(err.tick, int) and err.reason and f"tick {err.tick} failed" in str(err)
    assert a.tick == err.tick == good.tick
    with pytest.raises(ma.StepError) as e2:
        ma.rollout("elbow", "hill", np.ones((2, 2000, 2)), np.full((2, 2000, 1), 1e6),
                   substeps=1, overrides=[{}, {"muscle.*.k_t": 1e12, "joint.elbow.inertia": 1e-9}])
    assert e2.value.instance == 1 and "instance 1" in str(e2.value)


FUZZ = textwrap.dedent(
    """
    import numpy as np, muscle_actuator as ma
    rng = np.random.default_rng(2026)
    a = ma.Actuator("elbow", "hill")
    values = [0.5, -1.0, 2.0, np.nan, np.inf, -np.inf, 1e308, -1e-308, 0]
    dtypes = [np.float64, np.float32, np.int64, np.int8, np.bool_, np.complex128, object, "U3"]
    refused = accepted = 0
    for k in range(500):
        ndim = int(rng.integers(0, 4))
        shape = tuple(int(s) for s in rng.integers(0, 4, ndim))
        dt = dtypes[int(rng.integers(len(dtypes)))]
        try:
            x = rng.choice(values, size=shape).astype(dt)
        except (ValueError, TypeError, OverflowError):
            x = [["a"]] * int(rng.integers(0, 3))
        call = int(rng.integers(4))
        try:
            if call == 0:
                a.step(excitation=x)
            elif call == 1:
                a.step(excitation=[0.1, 0.1], external_torque=x)
            elif call == 2:
                a.rollout(x, outputs=["force"])
            else:
                ma.rollout("elbow", "hill", x, outputs=["force"], threads=2)
            accepted += 1
        except (ValueError, ma.StepError):
            refused += 1
        if a.tick > 10_000:
            a.reset()
    a.step(excitation=[0.5, 0.5], ticks=10)
    assert np.all(np.isfinite(a.muscle_state["force"]))
    print(refused, accepted)
    """
)


def test_a_fuzz_of_shapes_dtypes_and_values_never_crashes_the_interpreter():
    p = subprocess.run([sys.executable, "-c", FUZZ], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    refused, accepted = map(int, p.stdout.split())
    assert refused + accepted == 500 and refused > 100 and accepted > 10
