"""The Actuator from Python: names, state arrays, inputs by array and by name, driven joints,
saved states and pickles that resume bit for bit (in this process and in another)."""

from __future__ import annotations

import copy
import math
import pickle
import subprocess
import sys

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import ROOT, assert_bits_equal


def test_names_fields_and_initial_state():
    a = ma.Actuator("arm", "hill")
    assert a.muscles == ["TRIlong", "TRIlat", "TRImed", "BIClong", "BICshort", "BRA"]
    assert a.joints == ["shoulder", "elbow"] and a.model == "hill" and a.rate_hz == 1000.0
    assert set(a.muscle_state) == set(ma.MUSCLE_FIELDS) and len(ma.MUSCLE_FIELDS) == 25
    assert all(v.shape == (6,) for v in a.muscle_state.values())
    assert all(v.shape == (2,) for v in a.joint_state.values())
    assert a.stiffness_matrix.shape == (2, 2)
    assert a.tick == 0 and a.time == 0.0
    assert a.config["muscle"][0]["f_max"] == pytest.approx(798.52)
    assert "Actuator(model=\"hill\"" in repr(a)


def test_inputs_by_name_keep_the_others_and_are_held_over_ticks():
    a = ma.Actuator()  # the elbow, DM
    a.step(excitation=[0.5, 0.25], ticks=10)
    assert_bits_equal(a.muscle_state["excitation"], np.array([0.5, 0.25]), "held")
    a.step(excitation={"extensor": 1.0})
    assert list(a.muscle_state["excitation"]) == [0.5, 1.0]
    a.step(external_torque={"elbow": 0.7}, ticks=3)
    assert a.joint_state["external_torque"][0] == 0.7 and a.tick == 14
    # clamped as the node clamps
    a.step(excitation=[1.5, -2.0])
    assert list(a.muscle_state["excitation"]) == [1.0, 0.0]
    # a held excitation over 100 ticks = 100 calls of one tick
    b, c = ma.Actuator(), ma.Actuator()
    b.step(excitation=[0.8, 0.1], ticks=100)
    for _ in range(100):
        c.step(excitation=[0.8, 0.1])
    for f in ma.MUSCLE_FIELDS:
        assert_bits_equal(b.muscle_state[f], c.muscle_state[f], f)


def test_physics_has_the_right_sign_and_size():
    a = ma.Actuator("elbow", "huxley")
    a.step(excitation={"flexor": 1.0}, ticks=500)
    s = a.muscle_state
    # a fully active flexor pulls the elbow towards positive angles; force near Table 1's F0
    assert a.joint_state["position"][0] > 0.1
    assert 1000.0 < s["force"][0] < 4500.0 and s["force"][1] < s["force"][0]
    assert s["metabolic_power"][0] > 100.0 * max(s["metabolic_power"][1], 1e-9) and s["metabolic_power"][1] >= 0.0
    # the reset goes back to the initial state bit for bit
    fresh = ma.Actuator("elbow", "huxley")
    a.reset()
    for f in ma.MUSCLE_FIELDS:
        assert_bits_equal(a.muscle_state[f], fresh.muscle_state[f], f)


def test_get_state_and_set_state_branch_bit_for_bit():
    a = ma.Actuator("arm", "huxley")
    a.step(excitation=np.full(6, 0.3), ticks=50)
    saved = a.get_state()
    assert saved.tick == 50
    u = np.random.default_rng(1).uniform(0, 1, (120, 6))
    first = a.rollout(u)
    a.set_state(saved)
    assert a.tick == 50
    again = a.rollout(u)
    for k in first:
        assert_bits_equal(first[k], again[k], k)
    # a state of another actuator kind is refused
    with pytest.raises(ValueError, match="another configuration"):
        ma.Actuator("elbow", "huxley").set_state(saved)


@pytest.mark.parametrize("model", ["hill", "huxley", "huxley-pde"])
def test_a_pickled_actuator_resumes_identically_here_and_in_another_process(model, tmp_path):
    a = ma.Actuator("elbow", model)
    a.step(excitation=[1.0, 0.2], ticks=37)  # mid-transient: the stepper carries history
    blob = pickle.dumps(a)
    u = np.tile([[0.1, 0.9]], (80, 1))
    here = pickle.loads(blob).rollout(u, outputs=["force", "fiber_length", "joint.position"])
    want = a.copy().rollout(u, outputs=["force", "fiber_length", "joint.position"])
    for k in want:
        assert_bits_equal(here[k], want[k], k)
    (tmp_path / "a.pkl").write_bytes(blob)
    script = (
        "import pickle, sys, numpy as np\n"
        "a = pickle.loads(open(sys.argv[1], 'rb').read())\n"
        "out = a.rollout(np.tile([[0.1, 0.9]], (80, 1)), outputs=['force', 'fiber_length', 'joint.position'])\n"
        "np.savez(sys.argv[2], **out)\n"
    )
    subprocess.run([sys.executable, "-c", script, str(tmp_path / "a.pkl"), str(tmp_path / "o.npz")], check=True, timeout=300)
    there = np.load(tmp_path / "o.npz")
    for k in want:
        assert_bits_equal(there[k], want[k], f"other process {k}")
    st = pickle.loads(pickle.dumps(a.get_state()))
    b = ma.Actuator("elbow", model)
    b.set_state(st)
    assert b.tick == 37
    assert_bits_equal(b.rollout(u, outputs=["force"])["force"], want["force"], "state pickle")


def test_copies_are_independent():
    a = ma.Actuator()
    b = copy.deepcopy(a)
    a.step(excitation=[1, 0], ticks=5)
    assert b.tick == 0 and a.tick == 5
    assert copy.copy(a).tick == 5


def test_a_driven_joint_follows_the_motion_set_and_reports_its_effort():
    cfg = {
        "joint": [{"name": "elbow", "driven": True, "inertia": 0.06}],
        "muscle": [
            {"name": "flexor", "span": [{"joint": "elbow", "moment_arm": 0.03}]},
            {"name": "extensor", "span": [{"joint": "elbow", "moment_arm": -0.03}]},
        ],
    }
    a = ma.Actuator(cfg, "hill")
    assert a.driven_joints == ["elbow"]
    a.set_joint_motion("elbow", 0.1, 0.5)
    a.step(excitation=[0.5, 0.0], ticks=10)
    # θ(t) = θ0 + ω t over each tick, carried on: 0.1 + 0.5 · 0.01
    assert a.joint_state["position"][0] == pytest.approx(0.105, abs=1e-12)
    eff = a.joint_efforts
    assert eff.shape == (1,) and math.isclose(eff[0], a.joint_state["torque"][0])
    assert eff[0] > 0.0  # the active flexor pulls towards positive angles
    with pytest.raises(ValueError, match="unknown joint"):
        a.set_joint_motion("knee", 0.0)
    with pytest.raises(ValueError, match="not driven"):
        ma.Actuator().set_joint_motion(0, 0.0)


def test_energy_model_and_overrides_change_what_they_name():
    u = np.full((200, 2), 0.6)
    umb = ma.Actuator("elbow", "hill").rollout(u, outputs=["phenomenological_power"])
    bha = ma.Actuator("elbow", "hill", energy_model="bhargava").rollout(u, outputs=["phenomenological_power"])
    assert not np.array_equal(umb["phenomenological_power"], bha["phenomenological_power"])
    stiff = ma.Actuator("elbow", "hill", overrides={"muscle.*.k_t": 5e6}).rollout(u, outputs=["tendon_length"])
    soft = ma.Actuator("elbow", "hill").rollout(u, outputs=["tendon_length"])
    assert stiff["tendon_length"][-1, 0] < soft["tendon_length"][-1, 0]
    assert (ROOT / "crates/core/configs/elbow.toml").exists()
    from_file = ma.Actuator(ROOT / "crates/core/configs/elbow.toml", "hill").rollout(u, outputs=["force"])
    assert_bits_equal(from_file["force"], ma.Actuator("elbow", "hill").rollout(u, outputs=["force"])["force"], "path")


def test_damaged_pickles_are_refused_with_a_message():
    blob = pickle.dumps(ma.Actuator("elbow", "hill"))
    data = ma.Actuator("elbow", "hill")._from_bytes  # the constructor pickles call
    with pytest.raises(ValueError):
        data(b"")
    good = ma.Actuator("elbow", "hill").__reduce__()[1][0]
    for cut in (1, 10, len(good) // 2, len(good) - 1):
        with pytest.raises(ValueError):
            data(good[:cut])
    flipped = bytearray(good)
    flipped[len(good) // 2] ^= 0x10
    with pytest.raises(ValueError, match="checksum|length|version|magic"):
        data(bytes(flipped))
    assert pickle.loads(blob).tick == 0
