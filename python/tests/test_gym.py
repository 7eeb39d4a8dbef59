"""The Gymnasium environments: registered on `import muscle_actuator` (and by Gymnasium's
`module:id` form), Gymnasium's own checker passes with rendering, wrong actions are refused with
the expected shape, seeds matter and repeat, the native vector environment's instances step
exactly as single environments, and autoreset follows Gymnasium's next-step rule."""

from __future__ import annotations

import pickle
import re
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")
from gymnasium.utils.env_checker import check_env  # noqa: E402

import muscle_actuator as ma  # noqa: E402
import muscle_actuator.gym as mgym  # noqa: E402
from muscle_actuator._registration import ENVS  # noqa: E402
from conftest import assert_bits_equal  # noqa: E402


def registered() -> list[str]:
    return sorted(k for k in gym.registry if k.startswith("muscle_actuator/"))


def test_every_environment_of_the_package_is_registered():
    assert registered() == sorted(ENVS) == sorted([mgym.ENV_ID, mgym.FAST_ENV_ID])


def test_the_fast_environment_is_the_hill_arm_on_equilibrium_fibres_and_rigid_tendons():
    env = gym.make(mgym.FAST_ENV_ID)
    act = env.unwrapped.actuator
    assert act.model == "hill"
    muscles = act.config["muscle"]
    assert len(muscles) == 6
    assert all(m["fibre"] == "equilibrium" and m["tendon"] == "rigid" for m in muscles)
    # the standard environment keeps the paper's formulation (written out only when not it)
    plain = gym.make(mgym.ENV_ID).unwrapped.actuator.config["muscle"]
    assert not any("fibre" in m or "tendon" in m for m in plain)
    # holding the flexors on bends the elbow here too
    obs, _ = env.reset(seed=3)
    for _ in range(30):
        obs, *_ = env.step(np.array([0, 0, 0, 1, 1, 1.0]))
    assert obs[1] > 0.3
    with pytest.raises(ma.ConfigError, match="expected one of elastic, rigid"):
        mgym.ArmReachEnv(model="hill", fibre="equilibrium", tendon="stiff")


@pytest.mark.parametrize("env_id", sorted(ENVS))
def test_gymnasiums_checker_passes_with_rendering(env_id):
    # Gymnasium's own checker, its warnings as errors; it also makes the environment anew in
    # every declared render mode (rgb_array) and checks the frames.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        env = gym.make(env_id, render_mode="rgb_array")
        check_env(env.unwrapped)
        env.reset(seed=0)
        frame = env.render()
        env.close()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3


def test_the_gym_extra_brings_what_the_environments_need():
    # rgb_array frames are drawn with matplotlib: `pip install muscle_actuator[gym]` brings it.
    import importlib.metadata

    reqs = importlib.metadata.requires("muscle_actuator") or []
    gym_extra = {re.split(r"[<>=;\s\[]", r, maxsplit=1)[0] for r in reqs if re.search(r"extra == .gym.", r)}
    assert {"gymnasium", "matplotlib"} <= gym_extra, reqs


def run_python(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=300)


def test_import_muscle_actuator_registers_the_environments():
    p = run_python(
        """
        import muscle_actuator, sys
        import gymnasium as gym
        assert "muscle_actuator.gym" not in sys.modules  # registered by name, imported on make
        env = gym.make("muscle_actuator/ArmReach-v0", model="hill")
        print(type(env.unwrapped).__name__, env.reset(seed=0)[0].shape)
        """
    )
    assert p.returncode == 0 and p.stdout.split() == ["ArmReachEnv", "(24,)"], p.stderr[-2000:]


def test_gymnasiums_module_form_needs_no_import_first():
    p = run_python(
        """
        import sys
        import gymnasium as gym
        assert "muscle_actuator" not in sys.modules
        env = gym.make("muscle_actuator:muscle_actuator/ArmReach-v0", model="hill")
        venv = gym.make_vec("muscle_actuator:muscle_actuator/ArmReach-v0", num_envs=2,
                            vectorization_mode="vector_entry_point", model="hill")
        print(type(env.unwrapped).__name__, type(venv.unwrapped).__name__)
        """
    )
    assert p.returncode == 0 and p.stdout.split() == ["ArmReachEnv", "ArmReachVectorEnv"], p.stderr[-2000:]


def test_the_package_imports_without_gymnasium():
    # sys.modules["gymnasium"] = None makes it unimportable, as if it were not installed.
    p = run_python(
        """
        import sys
        sys.modules["gymnasium"] = None
        import muscle_actuator as ma
        a = ma.Actuator("elbow", "hill")
        a.step(excitation=[0.5, 0.5], ticks=3)
        try:
            import muscle_actuator.gym
        except ImportError as e:
            print("gym:", e)
        """
    )
    assert p.returncode == 0, p.stderr[-2000:]
    assert "muscle_actuator.gym needs gymnasium" in p.stdout


def test_wrong_actions_are_refused_with_the_expected_shape():
    env = mgym.ArmReachEnv(model="hill")
    env.reset(seed=0)
    cases = [
        (np.zeros(5), r"^action has shape \[5\]: expected \[6\] \(muscles\)$"),
        (np.zeros((1, 6)), r"^action has shape \[1, 6\]: expected \[6\] \(muscles\)$"),
        (0.5, r"^action has shape \[\]: expected \[6\] \(muscles\)$"),
        (np.array([0.1, 0.2, np.nan, 0, 0, 0]), r"^action\[2\] = nan is not finite$"),
        (np.array([0, 0, 0, 0, 0, -np.inf]), r"^action\[5\] = -inf is not finite$"),
        (np.full(6, 0.5 + 1j), r"^action has dtype complex128: expected real numbers of shape \[6\]"),
        (["a"] * 6, r"^action has dtype <U1: expected real numbers of shape \[6\]"),
        ([[0.1], [0.1, 0.2]], r"^action must be an array of numbers of shape \[6\]"),
    ]
    for action, msg in cases:
        with pytest.raises(ma.InputError, match=msg):
            env.step(action)
    assert env._steps == 0  # nothing was stepped
    # every refusal is also a ValueError, as Gymnasium users catch
    with pytest.raises(ValueError):
        env.step(np.zeros(5))


def test_accepted_actions_are_clipped_and_of_any_real_dtype():
    def first_step(action) -> np.ndarray:
        env = mgym.ArmReachEnv(model="hill")
        env.reset(seed=0)
        return env.step(action)[0]

    ones = first_step(np.ones(6))
    assert_bits_equal(first_step(np.full(6, 3.0)), ones, "above 1 clipped")
    assert_bits_equal(first_step(np.ones(6, dtype=np.int8)), ones, "int8")
    assert_bits_equal(first_step(np.ones(6, dtype=np.float32)), ones, "float32")
    assert_bits_equal(first_step([True] * 6), ones, "bool list")
    assert_bits_equal(first_step(np.full(6, -2.0)), first_step(np.zeros(6)), "below 0 clipped")


def test_the_vector_environment_refuses_wrong_actions():
    venv = mgym.ArmReachVectorEnv(num_envs=2, model="hill")
    venv.reset(seed=0)
    with pytest.raises(ma.InputError, match=r"^action has shape \[6\]: expected \[2, 6\] \(environments, muscles\)$"):
        venv.step(np.zeros(6))
    with pytest.raises(ma.InputError, match=r"^action\[1, 0\] = nan is not finite$"):
        venv.step(np.array([[0.0] * 6, [np.nan] + [0.0] * 5]))


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


def test_the_fast_environments_ticks_stay_close_to_the_fine_ones():
    # 2 ms ticks at tolerance 1e-3 against 1 ms ticks at the default tolerance, the same
    # formulation, 500 steps (5 s) of random actions: the joint angles within 2e-4 rad.
    fast = gym.make(mgym.FAST_ENV_ID).unwrapped
    fine = mgym.ArmReachEnv(model="hill", fibre="equilibrium", tendon="rigid")
    assert fast.dt == fine.dt == 0.01
    fast.reset(seed=0)
    fine.reset(seed=0)
    rng = np.random.default_rng(1)
    worst = 0.0
    for _ in range(500):
        a = rng.uniform(0, 1, 6)
        o_fast, o_fine = fast.step(a)[0], fine.step(a)[0]
        worst = max(worst, float(np.max(np.abs(o_fast[:2] - o_fine[:2]))))
    print(f"worst joint-angle difference {worst:.2e} rad")
    assert 0 < worst <= 2e-4


@pytest.mark.parametrize("env_id", sorted(ENVS))
def test_the_vector_environment_equals_single_environments(env_id):
    n, steps = 4, 100
    venv = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", model="hill")
    assert isinstance(venv.unwrapped, mgym.ArmReachVectorEnv)
    singles = [gym.make(env_id, model="hill").unwrapped for _ in range(n)]
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
