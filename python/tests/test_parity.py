"""The package is the command line's engine: `simulate` equals `muscle_actuator simulate --csv`
value for value, bit for bit; stepping an Actuator tick by tick (and by rollout) with the run's
own inputs gives the run again; batched rollouts equal separate actuators in any thread count."""

from __future__ import annotations

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import ROOT, assert_bits_equal, read_csv

CASES = [
    ("pulse", "hill", None),
    ("pulse", "huxley", None),
    ("pulse", "huxley-pde", None),
    ("energy-10hz", "huxley", None),
    ("energy-10hz", "hill", None),
    (str(ROOT / "scenarios/arm_cocontraction.toml"), "huxley", "arm"),
    (str(ROOT / "scenarios/elbow_cocontraction_ramp.toml"), "hill", None),
]


def csv_columns(run: ma.Run) -> dict[str, np.ndarray]:
    """The run's arrays laid out as the CSV's columns (NaN where the CSV is blank)."""
    df = run.to_pandas()
    return {c: df[c].to_numpy() for c in df.columns}


@pytest.mark.parametrize("scenario,model,config", CASES)
def test_simulate_equals_the_cli_csv(cli, scenario, model, config):
    args = ["simulate", scenario, "--model", model, "--csv", "-"]
    if config:
        args += ["--config", config]
    header, rows = read_csv(cli(*args).stdout)
    run = ma.simulate(scenario, model=model, config=config)
    assert run.model == model
    m = len(run.muscles)
    assert len(rows) == len(run.time) * m
    names = [r[1] for r in rows]
    assert names == run.muscles * len(run.time)
    time = np.array([float(r[0]) for r in rows[::m]])
    assert_bits_equal(time, run.time, "time")
    for c, field in enumerate(header[2:], start=2):
        cells = [r[c] for r in rows]
        if field in ma.MUSCLE_FIELDS:
            got = run[field].reshape(-1)
            want = np.array([float(x) for x in cells])
        else:
            joint, f = field.rsplit(".", 1)
            j = run.joints.index(joint)
            spans = [j in run.muscle_joints[i] for i in range(m)] * len(run.time)
            want = np.array([float(x) for x, s in zip(cells, spans) if s])
            got = np.repeat(run["joint." + f][:, j], m)[np.array(spans)]
            assert all(x == "" for x, s in zip(cells, spans) if not s)
        assert_bits_equal(got, want, f"{scenario} {model} {field}")


def test_to_pandas_is_the_csv(cli, tmp_path):
    pd = pytest.importorskip("pandas")
    out = tmp_path / "run.csv"
    cli("simulate", str(ROOT / "scenarios/arm_cocontraction.toml"), "--config", "arm", "--model", "hill", "--csv", str(out))
    want = pd.read_csv(out)
    got = ma.simulate(str(ROOT / "scenarios/arm_cocontraction.toml"), model="hill", config="arm").to_pandas()
    assert list(got.columns) == list(want.columns)
    for c in want.columns:
        if c == "name":
            assert list(got[c]) == list(want[c])
        else:
            assert_bits_equal(got[c].to_numpy(), want[c].to_numpy(), c)


@pytest.mark.parametrize("model", ["hill", "huxley"])
def test_stepping_with_the_runs_inputs_gives_the_run_again(model):
    scenario = str(ROOT / "scenarios/arm_cocontraction.toml")
    run = ma.simulate(scenario, model=model, config="arm")
    u = run["excitation"][1:]  # the excitation in force during each tick
    tau = run["joint.external_torque"][1:]
    act = ma.Actuator("arm", model)
    for name in ma.MUSCLE_FIELDS:
        assert_bits_equal(act.muscle_state[name], run[name][0], f"initial {name}")
    # tick by tick, one call per tick
    for t in range(len(u)):
        act.step(excitation=u[t], external_torque=tau[t])
        if t % 97 == 0 or t == len(u) - 1:
            for name in ma.MUSCLE_FIELDS:
                assert_bits_equal(act.muscle_state[name], run[name][t + 1], f"tick {t + 1} {name}")
            for name in ma.JOINT_FIELDS:
                assert_bits_equal(act.joint_state[name], run["joint." + name][t + 1], f"tick {t + 1} joint {name}")
            assert_bits_equal(act.stiffness_matrix, run["stiffness_matrix"][t + 1], f"tick {t + 1} K")
    assert act.tick == len(u) and act.time == run.time[-1]
    # the whole trajectory in one call
    again = ma.Actuator("arm", model).rollout(u, tau)
    for name, arr in again.items():
        assert_bits_equal(arr, run[name][1:], f"rollout {name}")


def sweep_inputs(b: int, t: int, m: int, seed: int = 7) -> np.ndarray:
    rng = np.random.default_rng(seed)
    steps = rng.uniform(0, 1, size=(b, t // 50 + 1, m))
    return np.repeat(steps, 50, axis=1)[:, :t, :]


@pytest.mark.parametrize("threads", [1, 2, 4])
def test_rollout_equals_separate_actuators_in_any_thread_count(threads):
    b, t = 8, 300
    u = sweep_inputs(b, t, 2)
    tau = np.linspace(-1, 1, b * t * 1).reshape(b, t, 1)
    overrides = [{"muscle.*.k_t": 1.0e5 * (1 + k), "joint.elbow.damping": 0.05 + 0.01 * k} for k in range(b)]
    out = ma.rollout("elbow", "huxley", u, tau, overrides=overrides, threads=threads)
    assert out["force"].shape == (b, t, 2) and out["joint.position"].shape == (b, t, 1)
    assert out["stiffness_matrix"].shape == (b, t, 1, 1)
    for k in range(b):
        alone = ma.Actuator("elbow", "huxley", overrides=overrides[k])
        for tick in range(t):
            alone.step(u[k, tick], tau[k, tick])
            if tick in (0, 149, t - 1):
                for name in ma.MUSCLE_FIELDS:
                    assert_bits_equal(out[name][k, tick], alone.muscle_state[name], f"{k} {tick} {name}")
                for name in ma.JOINT_FIELDS:
                    assert_bits_equal(out["joint." + name][k, tick], alone.joint_state[name], f"{k} {tick} {name}")
    # the overrides took: different tendons give different forces
    assert not np.array_equal(out["force"][0], out["force"][1])


def test_rollout_of_existing_actuators_continues_them_in_place():
    acts = [ma.Actuator("elbow", "hill") for _ in range(3)]
    twins = [a.copy() for a in acts]
    u = sweep_inputs(3, 200, 2, seed=3)
    first = ma.rollout(acts, excitation=u[:, :100], outputs=["force"], threads=2)
    second = ma.rollout(acts, excitation=u[:, 100:], outputs=["force", "joint.position"], threads=2)
    assert set(second) == {"force", "joint.position"}
    for k, twin in enumerate(twins):
        whole = twin.rollout(u[k], outputs=["force"])
        assert_bits_equal(np.concatenate([first["force"][k], second["force"][k]]), whole["force"], f"{k}")
        assert acts[k].tick == 200
