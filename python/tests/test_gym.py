"""The Gymnasium environment: Gymnasium's own checker passes, seeds matter and repeat, the native
vector environment's instances step exactly as single environments, and autoreset follows
Gymnasium's next-step rule."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")
from gymnasium.utils.env_checker import check_env  # noqa: E402

import muscle_actuator.gym as mgym  # noqa: E402
from conftest import assert_bits_equal  # noqa: E402


def test_gymnasiums_checker_passes():
    env = gym.make(mgym.ENV_ID, model="hill")
    check_env(env.unwrapped)
    env.close()


def test_seeds_matter_and_repeat():
    env = mgym.ArmReachEnv(model="hill")
    o1, i1 = env.reset(seed=1)
    o1b, _ = env.reset(seed=1)
    o2, i2 = env.reset(seed=2)
    assert_bits_equal(o1, o1b, "same seed")
    assert not np.array_equal(i1["target"], i2["target"])
    assert env.observation_space.contains(o1) and o1.shape == (24,)


def test_reaching_is_rewarded_and_effort_costs():
    env = mgym.ArmReachEnv(model="hill", effort_weight=1.0)
    env.reset(seed=0)
    _, r_idle, *_ = env.step(np.zeros(6))
    env.reset(seed=0)
    _, r_full, *_ = env.step(np.ones(6))
    # full co-contraction barely moves the arm in 10 ms but costs the effort term
    assert r_full < r_idle
    # holding the flexors (biceps, brachialis) on bends the elbow towards a flexed target
    env = mgym.ArmReachEnv(model="hill", effort_weight=0.0)
    obs, _ = env.reset(seed=3)
    flex = np.array([0, 0, 0, 1, 1, 1.0])
    first = None
    for _ in range(30):
        obs, r, term, trunc, _ = env.step(flex)
        first = r if first is None else first
    assert obs[1] > 0.3  # the elbow angle


def test_the_vector_environment_equals_single_environments():
    n, steps = 4, 100
    venv = gym.make_vec(mgym.ENV_ID, num_envs=n, vectorization_mode="vector_entry_point", model="hill")
    assert isinstance(venv.unwrapped, mgym.ArmReachVectorEnv)
    singles = [mgym.ArmReachEnv(model="hill") for _ in range(n)]
    obs, _ = venv.reset(seed=10)
    for i, e in enumerate(singles):
        o, _ = e.reset(seed=10 + i)
        assert_bits_equal(obs[i], o, f"reset {i}")
    rng = np.random.default_rng(0)
    for t in range(steps):
        actions = rng.uniform(0, 1, (n, 6))
        obs, rew, term, trunc, _ = venv.step(actions)
        for i, e in enumerate(singles):
            o, r, te, tr, _ = e.step(actions[i])
            assert_bits_equal(obs[i], o, f"step {t} env {i}")
            assert rew[i] == r and term[i] == te and trunc[i] == tr
    venv.close()


def test_autoreset_is_next_step():
    venv = mgym.ArmReachVectorEnv(num_envs=2, model="hill", max_episode_steps=3)
    single = mgym.ArmReachEnv(model="hill", max_episode_steps=3)
    venv.reset(seed=5)
    single.reset(seed=5)
    a = np.full((2, 6), 0.5)
    for _ in range(2):
        venv.step(a)
    obs, rew, term, trunc, _ = venv.step(a)
    assert trunc.all() and not term.any()
    obs, rew, term, trunc, info = venv.step(a)  # the reset step: action ignored, reward 0
    assert (rew == 0).all() and not trunc.any()
    # the reset drew a new target from the instance's own generator
    assert not np.array_equal(info["target"][0], single.reset(seed=5)[1]["target"])


def test_render_gives_an_rgb_frame_and_the_env_pickles():
    pytest.importorskip("matplotlib")
    env = mgym.ArmReachEnv(model="hill", render_mode="rgb_array")
    env.reset(seed=0)
    env.step(np.full(6, 0.2))
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
    assert frame.std() > 1.0  # not a blank image
    env2 = pickle.loads(pickle.dumps(env))
    a = np.full(6, 0.7)
    assert_bits_equal(env2.step(a)[0], env.step(a)[0], "pickled env")


def test_make_env_needs_no_registry():
    env = mgym.make_env({"model": "hill", "frame_skip": 5})
    obs, _ = env.reset(seed=0)
    assert obs.shape == (24,)
