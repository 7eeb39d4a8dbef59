"""The Python package's speed, beside the Rust it wraps and beside MuJoCo, in one run.

    python benches/python_bench.py [--limb-bin PATH] [--reps N] [--skip overhead,throughput,mujoco,gym,myosuite]

(benches/python-bench.sh builds or takes the wheel, installs it with numpy, mujoco and gymnasium
into a bench venv, builds the `limb` bench binary and runs this with --limb-bin.)

Prints Markdown tables (docs/benchmarks.md#python); every figure is the median of --reps
repetitions (default 5; at least 15 for the per-call figures), interleaved where two are
compared, with the load average before and after each table:

1. ``Actuator.step(ticks=1)`` per call on the elbow (DM and Hill), with a 2-element numpy
   excitation and with none, beside the tick alone in the same process (``step(ticks=20000)``
   and ``rollout`` of 20,000 ticks, per tick); the overhead per call is the difference, and the
   calls that take it apart (a property read, ``step(ticks=0)``); the fixed cost of a call of
   ``Actuator.rollout`` and of ``ma.rollout`` (one tick).
2. ``rollout`` of 64 ``arm`` actuators × 1000 ticks, DM, under benches/limb.rs's realistic load
   (every joint's two muscles get new random excitations every 100 ms, the joints' phases
   spread over the 100 ms, limb.rs's generator and seeds), outputs=["force"], on 1 and 2
   threads, beside ``limb`` (LIMB_CASES=arm LIMB_MODELS=huxley, run between the repetitions):
   actuator-ticks per second, the 2-thread speed-up, the cores the process got (CPU / wall) and
   Python/Rust per actuator-tick; given actuators (built before the clock) and new ones.
3. MuJoCo's ``rollout`` of a two-muscle hinge like the default elbow (the MJCF below) beside
   ``ma.rollout`` of the elbow, same controls: µs per two-muscle step and muscle-ticks per
   second, 1 × 100,000 steps and 64 × 1000 (a slowly varying co-contraction), and 64 × 20 after
   a full flexor step from rest.
4. ``muscle_actuator/ArmReach-v0``: the native vector environment (64 instances, random
   actions), DM and Hill, env-steps per second and the share of it inside ``rollout``; and the
   single environment's steps per second.
5. ``ArmReach-v0`` (DM, Hill) and ``ArmReachFast-v0`` beside MyoSuite's
   ``myoElbowPose1D6MRandom-v0`` (if MyoSuite is installed), single environments, random
   actions, interleaved: simulated seconds per wall second, and each environment's own cost per
   step beyond the stepping.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import time

import numpy as np

import muscle_actuator as ma

T_BIG = 20_000  # ticks of the "tick alone" calls
N_CALLS = 20_000  # calls of step(ticks=1) per repetition


def load() -> str:
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def median(xs) -> float:
    return float(np.median(np.asarray(xs, dtype=float)))


def timed(fn) -> float:
    """Seconds one call of ``fn`` takes."""
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def timed_cpu(fn) -> tuple[float, float]:
    """Wall seconds and CPU seconds (this process, all threads) of one call of ``fn``."""
    c0, t0 = time.process_time(), time.perf_counter()
    fn()
    return time.perf_counter() - t0, time.process_time() - c0


class Table:
    """A Markdown table printed with the load average before and after its measurements."""

    def __init__(self, title: str, header: list[str]) -> None:
        self.title, self.header, self.rows = title, header, []
        self.before = load()

    def row(self, *cells) -> None:
        self.rows.append([c if isinstance(c, str) else f"{c:.3g}" for c in cells])

    def show(self, note: str = "") -> None:
        print(f"\n### {self.title}\n")
        print(f"load average {self.before} before, {load()} after{note}\n")
        print("| " + " | ".join(self.header) + " |")
        print("|" + "---|" * len(self.header))
        for r in self.rows:
            print("| " + " | ".join(r) + " |")


# 1. The cost of a call ------------------------------------------------------------------------


def step_overhead(reps: int) -> None:
    reps = max(reps, 15)  # cheap (0.4 s a repetition), and the differences are small
    t = Table(
        "`Actuator.step(ticks=1)` against the tick alone (elbow, held co-contraction 0.6 / 0.3), "
        "per call or tick",
        ["model", "tick alone: `step(ticks=20000)` / 20000", "`rollout` of 20000 / 20000",
         "`step(u, ticks=1)`", "`step(ticks=1)`", "overhead with u / without",
         "`step(u, ticks=0)`", "`step(ticks=0)`", "`a.tick`"],
    )
    for model in ["huxley", "hill"]:
        a = ma.Actuator("elbow", model)
        u = np.array([0.6, 0.3])
        a.step(u, ticks=2000)  # to the held state, where every tick costs the same
        uu = np.tile(u, (T_BIG, 1))
        step = a.step

        def u1():
            for _ in range(N_CALLS):
                step(u, ticks=1)

        def none1():
            for _ in range(N_CALLS):
                step(ticks=1)

        def u0():
            for _ in range(N_CALLS):
                step(u, ticks=0)

        def none0():
            for _ in range(N_CALLS):
                step(ticks=0)

        def getter():
            for _ in range(N_CALLS):
                a.tick

        cases = {
            "big": (lambda: step(ticks=T_BIG), T_BIG),
            "rollout": (lambda: a.rollout(uu, outputs=["force"]), T_BIG),
            "u1": (u1, N_CALLS),
            "none1": (none1, N_CALLS),
            "u0": (u0, N_CALLS),
            "none0": (none0, N_CALLS),
            "getter": (getter, N_CALLS),
        }
        res: dict[str, list[float]] = {k: [] for k in cases}
        order = list(cases)
        for r in range(reps):
            # Forwards and backwards in turn, so that a drift of the machine's speed weighs on
            # every case alike; the overheads are medians of the differences within a repetition.
            for k in order if r % 2 == 0 else order[::-1]:
                fn, n = cases[k]
                res[k].append(timed(fn) * 1e6 / n)
        m = {k: median(v) for k, v in res.items()}
        over_u = median(np.subtract(res["u1"], res["big"]))
        over_none = median(np.subtract(res["none1"], res["big"]))
        t.row(
            "DM" if model == "huxley" else "Hill",
            f"{m['big']:.2f} µs",
            f"{m['rollout']:.2f} µs",
            f"{m['u1']:.2f} µs",
            f"{m['none1']:.2f} µs",
            f"{over_u:.2f} / {over_none:.2f} µs",
            f"{m['u0'] * 1e3:.0f} ns",
            f"{m['none0'] * 1e3:.0f} ns",
            f"{m['getter'] * 1e3:.0f} ns",
        )
    t.show(f"; {N_CALLS} calls or {T_BIG} ticks per repetition, median of {reps}")
    batch_call(reps)


def batch_call(reps: int) -> None:
    """The fixed cost of a call of ``Actuator.rollout`` and ``ma.rollout`` (one Hill tick)."""
    t = Table("The fixed cost of a rollout call (one elbow, one Hill tick, outputs=[\"force\"])",
              ["call", "µs per call", "beyond the tick"])
    a = ma.Actuator("elbow", "hill")
    u1, u = np.full((1, 2), 0.3), np.full((1, 1, 2), 0.3)
    a.step(u1[0], ticks=2000)
    n = 2000

    def batch(threads: int):
        def run():
            for _ in range(n):
                ma.rollout([a], excitation=u, outputs=["force"], threads=threads)

        return run

    cases = {
        "`a.rollout(u[1, 2])`": (lambda: [a.rollout(u1, outputs=["force"]) for _ in range(n)], n),
        "`ma.rollout([a], u[1, 1, 2], threads=1)`": (batch(1), n),
        "`ma.rollout([a], u[1, 1, 2], threads=2)`": (batch(2), n),
        "tick": (lambda: a.step(ticks=T_BIG), T_BIG),
    }
    res: dict[str, list[float]] = {k: [] for k in cases}
    for _ in range(reps):
        for k, (fn, m) in cases.items():
            res[k].append(timed(fn) * 1e6 / m)
    tick = median(res.pop("tick"))
    for k, v in res.items():
        t.row(k, f"{median(v):.2f}", f"{median(v) - tick:.2f}")
    t.show(f"; {n} calls per repetition, median of {reps}; the tick alone {tick:.2f} µs")


# 2. Throughput against limb.rs ----------------------------------------------------------------


class Lcg:
    """benches/limb.rs's generator in [0, 1)."""

    def __init__(self, seed: int) -> None:
        self.s = seed

    def next(self) -> float:
        self.s = (self.s * 6364136223846793005 + 1442695040888963407) % (1 << 64)
        return (self.s >> 11) / float(1 << 53)


def realistic(batch: int, ticks: int, muscles: int, u0: np.ndarray) -> np.ndarray:
    """limb.rs's realistic load as (batch, ticks, muscles): instance b is limb.rs's repetition
    b (seed 17 + b); pair j (muscles 2j, 2j+1) gets new values at the ticks k with
    (k + j·100 / pairs) % 100 = 0 and holds them; before its first, the initial excitation."""
    pairs = muscles // 2
    u = np.empty((batch, ticks, muscles))
    for b in range(batch):
        rng, cur = Lcg(17 + b), u0.copy()
        for k in range(ticks):
            for j in range(pairs):
                if (k + j * 100 // max(pairs, 1)) % 100 == 0:
                    cur[2 * j] = rng.next()
                    cur[2 * j + 1] = rng.next()
            u[b, k] = cur
    return u


def limb_rust(limb_bin: str) -> dict[str, float]:
    """µs per tick of the arm, DM, per load, from one run of the `limb` bench binary."""
    env = dict(os.environ, LIMB_CASES="arm", LIMB_MODELS="huxley")
    run = subprocess.run([limb_bin, "--bench"], env=env, check=True, capture_output=True, text=True)
    out = run.stdout
    fig = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) > 4 and f[0] == "arm" and f[1] == "huxley":
            fig[f[3]] = float(f[4])
    if "realistic" not in fig:
        raise SystemExit(f"no arm/huxley/realistic row in the limb output:\n{out}")
    return fig


def throughput(reps: int, limb_bin: str | None) -> None:
    b, ticks = 64, 1000
    proto = ma.Actuator("arm", "huxley")
    m = len(proto.muscles)
    u0 = proto.muscle_state["excitation"]
    u = realistic(b, ticks, m, u0)
    u5 = realistic(5, 2000, m, u0)  # limb.rs's work: its 5 repetitions of 2000 ticks
    t = Table(
        "`rollout` of 64 `arm` actuators × 1000 ticks, DM, limb.rs's realistic load, "
        "outputs=[\"force\"]",
        ["what", "threads", "µs per actuator-tick", "actuator-ticks/s", "ratio",
         "cores used (CPU / wall)"],
    )
    keys = ("new1", "new2", "old1", "old2", "5x2000", "rust", "build")
    res: dict[str, list[float]] = {k: [] for k in keys}
    cores: dict[str, list[float]] = {k: [] for k in keys}
    for _ in range(reps):
        for thr in (1, 2):
            w, c = timed_cpu(lambda: ma.rollout("arm", "huxley", u, outputs=["force"], threads=thr))
            res[f"new{thr}"].append(w * 1e6 / (b * ticks))
            cores[f"new{thr}"].append(c / w)
            fresh = [proto.copy() for _ in range(b)]
            w, c = timed_cpu(lambda: ma.rollout(fresh, excitation=u, outputs=["force"], threads=thr))
            res[f"old{thr}"].append(w * 1e6 / (b * ticks))
            cores[f"old{thr}"].append(c / w)
        # limb.rs's work and method: each repetition timed alone (35 ms or so), their median, so
        # that a preemption of this process weighs on both alike.
        alone = []
        for k in range(5):
            a = proto.copy()
            w, c = timed_cpu(lambda: a.rollout(u5[k], outputs=["force"]))
            alone.append(w * 1e6 / 2000)
            cores["5x2000"].append(c / w)
        res["5x2000"].append(median(alone))
        res["build"].append(timed(lambda: [ma.Actuator("arm", "huxley") for _ in range(b)]) * 1e3)
        if limb_bin:
            res["rust"].append(limb_rust(limb_bin)["realistic"])
    f = {k: median(v) for k, v in res.items() if v}
    cu = {k: f"{median(v):.2f}" for k, v in cores.items() if v}
    rust = f.get("rust")
    vs = (lambda x: f"Python / Rust {x / rust:.3f}") if rust else (lambda x: "—")
    for what, key in [("64 given actuators (`rollout(list, …)`), stepping only", "old"),
                      ("64 new actuators (`rollout(\"arm\", …)`), built and stepped", "new")]:
        one, two = f[f"{key}1"], f[f"{key}2"]
        t.row(what, "1", f"{one:.2f}", f"{1e6 / one:,.0f}", vs(one), cu[f"{key}1"])
        t.row(what, "2", f"{two:.2f}", f"{1e6 / two:,.0f}", f"speed-up {one / two:.2f}×",
              cu[f"{key}2"])
    t.row("limb.rs's work and method: 5 × `Actuator.rollout` of 2000 ticks, median", "1",
          f"{f['5x2000']:.2f}", f"{1e6 / f['5x2000']:,.0f}", vs(f["5x2000"]), cu["5x2000"])
    if rust:
        t.row("Rust: `LIMB_CASES=arm cargo bench --bench limb`, arm huxley realistic", "1",
              f"{rust:.2f}", f"{1e6 / rust:,.0f}", "1", "—")
    t.show(f"; median of {reps}, the limb binary run between the repetitions; building 64 `arm` "
           f"actuators (`Actuator(\"arm\", \"huxley\")`) takes {f['build']:.1f} ms")


# 3. MuJoCo -------------------------------------------------------------------------------------

# A hinge like the default elbow: inertia 0.06 kg m² about the hinge (no gravity), damping
# 0.05 N m s/rad, range ±π/2, two fixed tendons of ±0.03 m per rad (a 3 cm pulley), a MuJoCo
# muscle of 3913 N on each; the tendons' length range is the joint range times 3 cm.
MJCF = """
<mujoco model="elbow">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.001" gravity="0 0 0"/>
  <worldbody>
    <body name="forearm">
      <joint name="elbow" type="hinge" axis="0 1 0" damping="0.05" range="-1.5707963 1.5707963"/>
      <inertial pos="0 0 0" mass="1" diaginertia="0.06 0.06 0.06"/>
    </body>
  </worldbody>
  <tendon>
    <fixed name="flexor"><joint joint="elbow" coef="0.03"/></fixed>
    <fixed name="extensor"><joint joint="elbow" coef="-0.03"/></fixed>
  </tendon>
  <actuator>
    <muscle name="flexor" tendon="flexor" force="3913" lengthrange="-0.0471239 0.0471239"/>
    <muscle name="extensor" tendon="extensor" force="3913" lengthrange="-0.0471239 0.0471239"/>
  </actuator>
</mujoco>
"""


def cocontraction(batch: int, ticks: int) -> np.ndarray:
    """A slowly varying co-contraction (batch, ticks, 2): the flexor between 0.6 and 0.8 over a
    2 s period (instance b's phase b / batch of it), the extensor at 0.3."""
    k = np.arange(ticks)[None, :] * 1e-3 + 2.0 * np.arange(batch)[:, None] / batch
    u = np.empty((batch, ticks, 2))
    u[:, :, 0] = 0.7 - 0.1 * np.cos(np.pi * k)
    u[:, :, 1] = 0.3
    return u


def mujoco_vs(reps: int) -> None:
    import mujoco
    from mujoco import rollout

    model = mujoco.MjModel.from_xml_string(MJCF)
    data = [mujoco.MjData(model) for _ in range(2)]
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    x0 = np.zeros((1, mujoco.mj_stateSize(model, spec)))
    mujoco.mj_getState(model, data[0], x0[0], spec)
    protos = {mod: ma.Actuator("elbow", mod) for mod in ("huxley", "hill")}
    # The formulations of docs/model.md §5b: DM on equilibrium fibres, Hill on rigid tendons.
    names = protos["hill"].muscles
    eq = {f"muscle.{n}.fibre": "equilibrium" for n in names}
    rigid = {**eq, **{f"muscle.{n}.tendon": "rigid" for n in names}}
    protos["huxley-eq"] = ma.Actuator("elbow", "huxley", overrides=eq)
    protos["hill-rigid"] = ma.Actuator("elbow", "hill", overrides=rigid)
    loads = {
        "1 × 100,000, co-contraction": cocontraction(1, 100_000),
        "64 × 1000, co-contraction": cocontraction(64, 1000),
        "64 × 20, after a full flexor step from rest": np.broadcast_to([1.0, 0.0], (64, 20, 2)).copy(),
    }

    def ours(mod: str, u: np.ndarray, threads: int) -> float:
        """Seconds of ma.rollout of len(u) elbows at rest, given (built before the clock)."""
        fresh = [protos[mod].copy() for _ in range(u.shape[0])]
        return timed(lambda: ma.rollout(fresh, excitation=u, outputs=["force"], threads=threads))

    t = Table(
        f"MuJoCo {mujoco.__version__} `rollout.Rollout(nthread=1)` against `ma.rollout(threads=1)`, "
        "a two-muscle hinge",
        ["load (instances × ticks)", "MuJoCo µs/step", "DM µs/tick", "Hill µs/tick",
         "MuJoCo muscle-ticks/s", "DM / MuJoCo muscle-ticks/s", "Hill / MuJoCo"],
    )
    kinds = t2_kinds = ("huxley-eq", "hill-rigid")
    t2 = Table(
        "The same, the elbow on equilibrium fibres (DM) and rigid tendons (Hill): time per tick "
        "over MuJoCo's per step",
        ["load (instances × ticks)", "MuJoCo µs/step", "DM equilibrium µs/tick", "/ MuJoCo",
         "Hill rigid µs/tick", "/ MuJoCo"],
    )
    with rollout.Rollout(nthread=1) as r:
        for name, u in loads.items():
            b, n = u.shape[:2]
            res: dict[str, list[float]] = {k: [] for k in ("mj", "huxley", "hill", *kinds)}
            for _ in range(reps):
                res["mj"].append(timed(lambda: r.rollout(model, data[:1], x0, u)) * 1e6 / (b * n))
                for mod in ("huxley", "hill", *kinds):
                    res[mod].append(ours(mod, u, 1) * 1e6 / (b * n))
            mj, dm, hill = (median(res[k]) for k in ("mj", "huxley", "hill"))
            t.row(name, f"{mj:.3f}", f"{dm:.2f}", f"{hill:.2f}", f"{2e6 / mj:,.0f}",
                  f"{mj / dm:.3f}", f"{mj / hill:.3f}")
            dm_eq, hill_rigid = (median(res[k]) for k in t2_kinds)
            t2.row(name, f"{mj:.3f}", f"{dm_eq:.2f}", f"{dm_eq / mj:.2f}×", f"{hill_rigid:.2f}",
                   f"{hill_rigid / mj:.2f}×")
        u = loads["64 × 1000, co-contraction"]
        one = median([timed(lambda: r.rollout(model, data[:1], x0, u)) for _ in range(reps)])
    with rollout.Rollout(nthread=2) as r2:
        two = median([timed(lambda: r2.rollout(model, data, x0, u)) for _ in range(reps)])
    ours1 = median([ours("huxley", u, 1) for _ in range(reps)])
    ours2 = median([ours("huxley", u, 2) for _ in range(reps)])
    t2.show(f"; median of {reps}, the same repetitions as the table below")
    t.show(
        f"; median of {reps}; the elbows built before the clock starts. 64 × 1000 on 2 threads "
        f"(`Rollout(nthread=2)`, `threads=2`): MuJoCo speed-up {one / two:.2f}×, "
        f"DM {ours1 / ours2:.2f}×"
    )


# 4. The Gymnasium environments -----------------------------------------------------------------


def gym_envs(reps: int) -> None:
    import gymnasium as gym

    import muscle_actuator.gym as mgym

    n_envs, steps = 64, 400
    rng = np.random.default_rng(0)
    t = Table(
        "`muscle_actuator/ArmReach-v0`, random actions (frame_skip 10: 10 ticks a step)",
        ["environment", "model", "env-steps/s", "µs per env-step", "of which in `rollout`"],
    )
    for model in ["huxley", "hill"]:
        venv = gym.make_vec(
            mgym.ENV_ID, num_envs=n_envs, vectorization_mode="vector_entry_point", model=model
        )
        acts = rng.uniform(0.0, 1.0, (steps, n_envs, 6))
        total, inner = [], []
        for r in range(reps):
            venv.reset(seed=r)

            def run():
                for a in acts:
                    venv.step(a)

            total.append(timed(run) / (steps * n_envs))
            # The same rollouts alone, on copies of the instances (no resets, no observations),
            # as a share of this repetition's time.
            copies = [a.copy() for a in venv.unwrapped.actuators]
            exc = np.repeat(acts[:, :, None, :], 10, axis=2)

            def bare():
                for e in exc:
                    ma.rollout(copies, excitation=e, outputs=mgym._OUTPUTS)

            inner.append(timed(bare) / (steps * n_envs) / total[-1])
        venv.close()
        tot = median(total)
        t.row(f"vector, {n_envs} instances", model, f"{1 / tot:,.0f}", f"{tot * 1e6:.1f}",
              f"{median(inner):.0%}")
        env = gym.make(mgym.ENV_ID, model=model)
        single = []
        for r in range(reps):
            env.reset(seed=r)
            a1 = rng.uniform(0.0, 1.0, (steps, 6))

            def run1():
                for a in a1:
                    _, _, term, trunc, _ = env.step(a)
                    if term or trunc:
                        env.reset()

            single.append(timed(run1) / steps)
        env.close()
        s1 = median(single)
        t.row("single (`gym.make`)", model, f"{1 / s1:,.0f}", f"{s1 * 1e6:.1f}", "—")
    t.show(f"; {steps} vector steps or {steps} steps per repetition, median of {reps}")


# 5. Against MyoSuite -----------------------------------------------------------------------------

MYOSUITE_ENV = "myoElbowPose1D6MRandom-v0"


def myosuite_vs(reps: int) -> None:
    """``ArmReach-v0`` (DM, Hill) and ``ArmReachFast-v0`` beside MyoSuite's six-muscle elbow,
    single environments made with ``gym.make``, random actions, interleaved: simulated seconds
    per wall second, and the environment's own cost per step (its step less the bare stepping of
    the same actuator, ``step(u, ticks=frame_skip)``, on a copy)."""
    import gymnasium as gym

    import muscle_actuator.gym as mgym

    try:
        import myosuite  # noqa: F401  (registers MyoSuite's environments)
    except ImportError:
        print("\n(MyoSuite is not installed: pip install myosuite; its comparison is skipped)")
        return
    steps = 400
    envs = {
        f"MyoSuite {MYOSUITE_ENV}": gym.make(MYOSUITE_ENV),
        "`ArmReach-v0`, DM": gym.make(mgym.ENV_ID, model="huxley"),
        "`ArmReach-v0`, Hill": gym.make(mgym.ENV_ID, model="hill"),
        "`ArmReachFast-v0`": gym.make(mgym.FAST_ENV_ID),
    }
    rng = np.random.default_rng(0)
    sim: dict[str, list[float]] = {k: [] for k in envs}
    own: dict[str, list[float]] = {k: [] for k in envs}
    for rep in range(reps):
        for name, env in envs.items():
            acts = rng.uniform(0.0, 1.0, (steps,) + env.action_space.shape)
            env.reset(seed=rep)

            def run():
                for a in acts:
                    _, _, term, trunc, _ = env.step(a)
                    if term or trunc:
                        env.reset()

            wall = timed(run)
            sim[name].append(steps * env.unwrapped.dt / wall)
            if name.startswith("MyoSuite"):
                continue
            inner = env.unwrapped
            bare = inner.actuator.copy()
            skip = inner._task.frame_skip
            stepping = timed(lambda: [bare.step(inner._task.action(a), ticks=skip) for a in acts])
            own[name].append((wall - stepping) / steps)
    # The vector forms: ours native (its instances stepped together on every core), MyoSuite's
    # Gymnasium's synchronous vector of its environment.
    n_envs, v_steps = 16, 100
    vecs = {
        f"MyoSuite {MYOSUITE_ENV}, sync vector": gym.make_vec(
            MYOSUITE_ENV, num_envs=n_envs, vectorization_mode="sync"),
        "`ArmReachFast-v0`, native vector": gym.make_vec(
            mgym.FAST_ENV_ID, num_envs=n_envs, vectorization_mode="vector_entry_point"),
    }
    for name, venv in vecs.items():
        sim[name] = []
        dt = venv.unwrapped.dt if hasattr(venv.unwrapped, "dt") else venv.get_attr("dt")[0]
        for rep in range(reps):
            acts = rng.uniform(0.0, 1.0, (v_steps,) + venv.action_space.shape)
            venv.reset(seed=rep)
            wall = timed(lambda: [venv.step(a) for a in acts])
            sim[name].append(v_steps * n_envs * dt / wall)
        envs[name] = venv
    myo = median(sim[f"MyoSuite {MYOSUITE_ENV}"])
    myo_vec = median(sim[f"MyoSuite {MYOSUITE_ENV}, sync vector"])
    t = Table(
        f"Against MyoSuite {myosuite.__version__} (MuJoCo, rigid tendons), single environments, "
        "random actions",
        ["environment", "simulated s per wall s", "against MyoSuite", "step (sim. ms)",
         "environment's own µs per step"],
    )
    for name, env in envs.items():
        rate = median(sim[name])
        vector = "vector" in name
        mine = f"{median(own[name]) * 1e6:.1f}" if own.get(name) else "—"
        dt = env.unwrapped.dt if hasattr(env.unwrapped, "dt") else env.get_attr("dt")[0]
        t.row(name, f"{rate:.1f}", f"{rate / (myo_vec if vector else myo):.2f}×",
              f"{dt * 1e3:g}", mine)
    t.show(f"; {steps} steps per repetition (vectors: {v_steps} of {n_envs} instances), "
           f"median of {reps}; vectors against MyoSuite's vector")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--limb-bin", help="the built benches/limb.rs binary (cargo bench --no-run)")
    p.add_argument("--reps", type=int, default=5, help="repetitions per figure (median; >= 3)")
    p.add_argument("--skip", default="", help="comma-separated: overhead,throughput,mujoco,gym,myosuite")
    args = p.parse_args()
    if args.reps < 3:
        raise SystemExit("--reps must be >= 3")
    skip = set(filter(None, args.skip.split(",")))
    print(f"muscle_actuator {ma.__version__}, numpy {np.__version__}, "
          f"Python {platform.python_version()}, {os.cpu_count()} cores; "
          f"load average {load()} at the start")
    if "overhead" not in skip:
        step_overhead(args.reps)
    if "throughput" not in skip:
        throughput(args.reps, args.limb_bin)
    if "mujoco" not in skip:
        mujoco_vs(args.reps)
    if "gym" not in skip:
        gym_envs(args.reps)
    if "myosuite" not in skip:
        myosuite_vs(args.reps)
    print(f"\nload average {load()} at the end")


if __name__ == "__main__":
    main()
