"""The accuracy setting: the configuration's `[stepper]` table as the override
`stepper.tolerance` and the keyword `tolerance=` (docs/python.md#accuracy); bad values, and a
tolerance with fixed sub-steps, are refused on one line naming `stepper.tolerance`."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import assert_bits_equal


def forces(a: ma.Actuator, ticks: int = 300) -> np.ndarray:
    u = np.zeros((ticks, len(a.muscles)))
    u[20:120, 0] = 1.0  # a pulse of the flexor: a transient for the adaptive sub-steps
    return a.rollout(u, outputs=["force"])["force"]


def test_the_override_sets_the_tolerance_and_the_configuration_carries_it():
    default = ma.Actuator("elbow", "hill")
    assert "stepper" not in default.config
    tight = ma.Actuator("elbow", "hill", overrides={"stepper.tolerance": 1e-7})
    assert tight.config["stepper"] == {"tolerance": 1e-7}
    f_default, f_tight = forces(default), forces(tight)
    # A different stepping: not the same bits, but the same run within the default's accuracy.
    assert not np.array_equal(f_default, f_tight)
    np.testing.assert_allclose(f_tight, f_default, rtol=0, atol=1e-2 * f_default.max())
    # Hill's own tolerance, set explicitly, is the default stepping bit for bit.
    same = ma.Actuator("elbow", "hill", overrides={"stepper.tolerance": 5e-5})
    assert_bits_equal(forces(same), f_default, "tolerance 5e-5 vs Hill's default")


def test_the_keyword_is_the_override_and_wins_over_it():
    by_override = ma.Actuator("elbow", "huxley", overrides={"stepper.tolerance": 1e-6})
    by_keyword = ma.Actuator("elbow", "huxley", tolerance=1e-6)
    both = ma.Actuator("elbow", "huxley", overrides={"stepper.tolerance": 1e-3}, tolerance=1e-6)
    f = forces(by_override)
    assert_bits_equal(forces(by_keyword), f, "tolerance= vs override")
    assert_bits_equal(forces(both), f, "tolerance= after the override")
    assert by_keyword.config["stepper"]["tolerance"] == 1e-6


def test_rollout_and_simulate_take_it():
    u = np.zeros((2, 200, 2))
    u[:, 20:, 0] = 0.8
    out = ma.rollout("elbow", "hill", u, overrides=[{}, {"stepper.tolerance": 1e-7}], outputs=["force"])
    alone = ma.Actuator("elbow", "hill", tolerance=1e-7)
    assert_bits_equal(out["force"][1], alone.rollout(u[1], outputs=["force"])["force"], "instance 1")
    assert not np.array_equal(out["force"][0], out["force"][1])
    kw = ma.rollout("elbow", "hill", u, tolerance=1e-7, outputs=["force"])
    assert_bits_equal(kw["force"][0], out["force"][1], "rollout(tolerance=)")
    with pytest.raises(ma.ConfigError, match="apply to new actuators only"):
        ma.rollout([alone], excitation=u[:1], tolerance=1e-7)

    base = ma.simulate("pulse", model="hill")
    tight = ma.simulate("pulse", model="hill", tolerance=1e-7)
    as_dict = ma.simulate(
        "pulse", model="hill", config={"muscle": [{"name": "flexor"}, {"name": "extensor"}],
                                       "stepper": {"tolerance": 1e-7}}
    )
    assert_bits_equal(as_dict["force"], tight["force"], "simulate: tolerance= vs [stepper]")
    assert not np.array_equal(base["force"], tight["force"])


def test_saved_states_and_pickles_keep_it():
    a = ma.Actuator("arm", "huxley", tolerance=1e-6)
    a.step(excitation={"BIClong": 0.6, "BRA": 0.8}, ticks=50)
    state = a.get_state()
    expected = forces(a, 100)
    b = pickle.loads(pickle.dumps(a))
    a.set_state(state)
    assert_bits_equal(forces(a, 100), expected, "after set_state")
    # The pickle was taken after the rollout: it resumes from there, with the same tolerance.
    assert b.config["stepper"] == {"tolerance": 1e-6}
    c = pickle.loads(pickle.dumps(state))
    fresh = ma.Actuator("arm", "huxley", tolerance=1e-6)
    fresh.set_state(c)
    assert_bits_equal(forces(fresh, 100), expected, "a pickled saved state")
    # A saved state of another tolerance is another actuator's.
    other = ma.Actuator("arm", "huxley")
    with pytest.raises(ma.ConfigError, match="another configuration"):
        other.set_state(state)


@pytest.mark.parametrize("value", [0.0, -1e-6, 0.5, 1e-12, float("nan"), float("inf")])
def test_bad_values_are_refused_on_one_line(value):
    for make in (
        lambda: ma.Actuator(overrides={"stepper.tolerance": value}),
        lambda: ma.Actuator(tolerance=value),
    ):
        with pytest.raises(ma.ConfigError) as e:
            make()
        msg = str(e.value)
        assert "stepper.tolerance" in msg and "\n" not in msg, msg


def test_fixed_sub_steps_refuse_a_tolerance():
    for make in (
        lambda: ma.Actuator("elbow", "hill", substeps=8, tolerance=1e-6),
        lambda: ma.Actuator("elbow", "huxley-pde", tolerance=1e-6),
        lambda: ma.simulate("pulse", model="hill", substeps=8, tolerance=1e-6),
    ):
        with pytest.raises(ma.ConfigError) as e:
            make()
        msg = str(e.value)
        assert msg.startswith("stepper.tolerance applies to adaptive sub-steps") and "\n" not in msg, msg
    with pytest.raises(ma.ConfigError, match="unknown key `tol`; did you mean `tolerance`"):
        ma.Actuator(overrides={"stepper.tol": 1e-6})
