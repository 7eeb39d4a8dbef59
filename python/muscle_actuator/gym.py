"""Gymnasium environments on the ``arm`` (OpenSim's arm26: shoulder and elbow, six muscles).

``muscle_actuator/ArmReach-v0``: bring the two joints to a target pair of angles drawn at each
reset, with the six muscles' excitations as the action.

- observation (24 values, float64): joint angles (2, rad), joint velocities (2, rad/s), the
  target angles (2, rad), muscle activations (6), tendon forces over f_max (6), fibre lengths
  over l_opt (6);
- action: excitations in [0, 1] (6), held over ``frame_skip`` ticks (of 1 ms: ``rate_hz``);
- reward: ``-|θ - θ*|₂ - effort_weight · mean(u²)`` per step;
- an episode ends by truncation after ``max_episode_steps`` steps (2 s by default); a failed tick
  ends it as terminated with ``reward = -failure_penalty`` and ``info["step_error"]``.

``fibre`` and ``tendon`` set every muscle's fibre and tendon kind (docs/configuration.md "Fibre
and tendon kinds"), ``rate_hz`` the tick rate and ``tolerance`` the stepper's (docs/python.md
"Accuracy"). ``muscle_actuator/ArmReachFast-v0`` is the same task (10 ms a step) with the Hill
model on equilibrium fibres and rigid tendons (the formulation MuJoCo and MyoSuite use), ticks of
2 ms (``rate_hz=500``, ``frame_skip=5``, MyoSuite's time step) and tolerance 1e-3: the arm's
joint angles stay within 1e-4 rad of the 1 kHz, default-tolerance run over 5 s of random actions
(docs/benchmarks.md "Python").

:class:`ArmReachVectorEnv` is the native vector environment
(``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")``): its instances are stepped
together by :func:`muscle_actuator.rollout` on every core, and instance ``i`` reset with seed
``s + i`` steps exactly as a single environment reset with seed ``s + i``. It resets finished
instances at their next step (Gymnasium's next-step autoreset). :func:`make_env` is a plain
creator for frameworks whose workers do not see Gymnasium's registry (RLlib).

An action of another shape, of a type that is not real numbers, or with a NaN or an infinity is
refused with :class:`muscle_actuator.InputError` naming what was expected; excitations outside
[0, 1] are clipped, as the node clamps them. ``render_mode="rgb_array"`` needs matplotlib (in
the ``gym`` extra).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

try:
    import gymnasium as gym
    from gymnasium import spaces
    from gymnasium.utils import seeding
    from gymnasium.vector import AutoresetMode, VectorEnv
except ImportError as e:  # pragma: no cover - depends on the environment
    raise ImportError("muscle_actuator.gym needs gymnasium: pip install 'gymnasium>=1.0'") from e

from . import Actuator, ConfigError, InputError, StepError, rollout
from ._registration import ENVS, register_envs

ENV_ID = "muscle_actuator/ArmReach-v0"
FAST_ENV_ID = "muscle_actuator/ArmReachFast-v0"
#: Target angles are drawn uniformly from these ranges, rad (inside the joints' ranges).
TARGET_LOW = np.array([0.0, 0.3])
TARGET_HIGH = np.array([1.2, 1.8])
_OUTPUTS = ["joint.position", "joint.velocity", "activation", "force", "fiber_length"]


class _Task:
    """What the single and the vector environment share: the actuator's set-up, the observation
    and the reward (one instance)."""

    def __init__(
        self,
        model: str,
        frame_skip: int,
        max_episode_steps: int,
        effort_weight: float,
        failure_penalty: float,
        config: Any,
        fibre: str | None = None,
        tendon: str | None = None,
        rate_hz: float = 1000.0,
        tolerance: float | None = None,
    ) -> None:
        if frame_skip < 1 or max_episode_steps < 1:
            raise ConfigError("frame_skip and max_episode_steps must be >= 1")
        self.model, self.config = model, config
        self.rate_hz, self.tolerance = float(rate_hz), tolerance
        self.frame_skip, self.max_episode_steps = int(frame_skip), int(max_episode_steps)
        self.effort_weight, self.failure_penalty = float(effort_weight), float(failure_penalty)
        # Every muscle's fibre and tendon kind, if given (docs/configuration.md).
        self.overrides: dict[str, Any] = {
            f"muscle.*.{key}": value
            for key, value in (("fibre", fibre), ("tendon", tendon))
            if value is not None
        }
        probe = self.actuator()
        cfg = probe.config
        self.f_max = np.array([m["f_max"] for m in cfg["muscle"]])
        self.l_opt = np.array([m["l_opt"] for m in cfg["muscle"]])
        self.m, self.j = len(probe.muscles), len(probe.joints)
        # Bounds wide enough for any state the limb reaches: the joint ranges with their limit
        # springs' overshoot, velocities to 100 rad/s, forces to 5 f_max, lengths to 5 l_opt.
        lo = np.array([j["min_angle"] for j in cfg["joint"]]) - 1.0
        hi = np.array([j["max_angle"] for j in cfg["joint"]]) + 1.0
        vel = np.full(self.j, 100.0)
        low = np.concatenate([lo, -vel, TARGET_LOW, np.zeros(3 * self.m)])
        high = np.concatenate([hi, vel, TARGET_HIGH, np.ones(self.m), np.full(2 * self.m, 5.0)])
        self.observation_space = spaces.Box(low, high, dtype=np.float64)
        self.action_space = spaces.Box(0.0, 1.0, shape=(self.m,), dtype=np.float64)

    def actuator(self) -> Actuator:
        return Actuator(
            self.config, self.model, self.rate_hz, overrides=self.overrides, tolerance=self.tolerance
        )

    def initial(self, act: Actuator) -> dict[str, np.ndarray]:
        return act.observe(_OUTPUTS)

    def observation(self, out: dict[str, np.ndarray], target: np.ndarray) -> np.ndarray:
        return np.concatenate(
            [
                out["joint.position"],
                out["joint.velocity"],
                target,
                out["activation"],
                out["force"] / self.f_max,
                out["fiber_length"] / self.l_opt,
            ]
        )

    def reward(self, out: dict[str, np.ndarray], target: np.ndarray, u: np.ndarray) -> float:
        d = out["joint.position"] - target
        return -math.sqrt(float(d @ d)) - self.effort_weight * float(u @ u) / len(u)

    def action(self, action: Any, shape: tuple[int, ...] | None = None) -> np.ndarray:
        """The action as excitations of ``shape`` (default: one per muscle), clipped to [0, 1];
        refused with :class:`InputError` if of another shape, not real numbers, or not finite."""
        shape = (self.m,) if shape is None else shape
        if type(action) is np.ndarray and action.dtype == np.float64 and action.shape == shape:
            u = action.copy()  # the common case, checked without building messages
        else:
            want = f"{list(shape)} (" + ("environments, " if len(shape) == 2 else "") + "muscles)"
            try:
                a = np.asarray(action)
            except (ValueError, TypeError) as e:  # ragged nested sequences
                raise InputError(f"action must be an array of numbers of shape {want}: {e}") from None
            if a.dtype.kind not in "biuf":
                raise InputError(f"action has dtype {a.dtype}: expected real numbers of shape {want}")
            if a.shape != shape:
                raise InputError(f"action has shape {list(a.shape)}: expected {want}")
            u = a.astype(np.float64)
        if not np.isfinite(u).all():
            k = tuple(int(i) for i in np.argwhere(~np.isfinite(u))[0])
            raise InputError(f"action{list(k)} = {u[k]} is not finite")
        return np.clip(u, 0.0, 1.0, out=u)


class ArmReachEnv(gym.Env):
    """Reach a target pair of joint angles with the arm's six muscles (module docstring)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self,
        model: str = "huxley",
        frame_skip: int = 10,
        max_episode_steps: int = 200,
        effort_weight: float = 0.1,
        failure_penalty: float = 10.0,
        render_mode: str | None = None,
        config: Any = "arm",
        fibre: str | None = None,
        tendon: str | None = None,
        rate_hz: float = 1000.0,
        tolerance: float | None = None,
    ) -> None:
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ConfigError(f"render_mode {render_mode!r}: expected one of {self.metadata['render_modes']}")
        self._task = _Task(
            model, frame_skip, max_episode_steps, effort_weight, failure_penalty, config, fibre,
            tendon, rate_hz, tolerance,
        )
        self.observation_space = self._task.observation_space
        self.action_space = self._task.action_space
        self.render_mode = render_mode
        self._actuator = self._task.actuator()
        self._target = np.zeros(self._task.j)
        self._steps = 0
        self._last: dict[str, np.ndarray] = self._task.initial(self._actuator)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        self._actuator.reset()
        self._target = self.np_random.uniform(TARGET_LOW, TARGET_HIGH)
        self._steps = 0
        self._last = self._task.initial(self._actuator)
        return self._task.observation(self._last, self._target), {"target": self._target.copy()}

    def step(self, action: Any):
        u = self._task.action(action)
        self._steps += 1
        info: dict[str, Any] = {"target": self._target.copy()}
        try:
            # The excitation held over the step's ticks in one call, then its end read in one.
            self._actuator.step(u, ticks=self._task.frame_skip)
        except StepError as e:
            info["step_error"] = str(e)
            obs = self._task.observation(self._last, self._target)
            return obs, -self._task.failure_penalty, True, False, info
        self._last = self._actuator.observe(_OUTPUTS)
        obs = self._task.observation(self._last, self._target)
        reward = self._task.reward(self._last, self._target, u)
        truncated = self._steps >= self._task.max_episode_steps
        return obs, reward, False, truncated, info

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        from ._render import arm_frame

        return arm_frame(self._last, self._target, self._actuator.muscles, self._task.f_max)

    @property
    def dt(self) -> float:
        """Simulated time a step covers, s (``frame_skip`` ticks)."""
        return self._task.frame_skip / self._actuator.rate_hz

    @property
    def actuator(self) -> Actuator:
        """The stepped actuator (read its full state with ``observe()``)."""
        return self._actuator


class ArmReachVectorEnv(VectorEnv):
    """``num_envs`` instances of :class:`ArmReachEnv` stepped together on every core."""

    metadata = {"render_modes": ["rgb_array"], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        num_envs: int = 8,
        model: str = "huxley",
        frame_skip: int = 10,
        max_episode_steps: int = 200,
        effort_weight: float = 0.1,
        failure_penalty: float = 10.0,
        render_mode: str | None = None,
        config: Any = "arm",
        threads: int | None = None,
        fibre: str | None = None,
        tendon: str | None = None,
        rate_hz: float = 1000.0,
        tolerance: float | None = None,
    ) -> None:
        if num_envs < 1:
            raise ConfigError("num_envs must be >= 1")
        self._task = _Task(
            model, frame_skip, max_episode_steps, effort_weight, failure_penalty, config, fibre,
            tendon, rate_hz, tolerance,
        )
        self.num_envs = int(num_envs)
        self.render_mode = render_mode
        self.single_observation_space = self._task.observation_space
        self.single_action_space = self._task.action_space
        self.observation_space = gym.vector.utils.batch_space(self.single_observation_space, self.num_envs)
        self.action_space = gym.vector.utils.batch_space(self.single_action_space, self.num_envs)
        self._threads = threads
        self._actuators = [self._task.actuator() for _ in range(self.num_envs)]
        self._rngs = [seeding.np_random()[0] for _ in range(self.num_envs)]
        self._targets = np.zeros((self.num_envs, self._task.j))
        self._steps = np.zeros(self.num_envs, dtype=np.int64)
        self._pending_reset = np.zeros(self.num_envs, dtype=bool)
        self._last = [self._task.initial(a) for a in self._actuators]

    def _reset_one(self, i: int) -> np.ndarray:
        self._actuators[i].reset()
        self._targets[i] = self._rngs[i].uniform(TARGET_LOW, TARGET_HIGH)
        self._steps[i] = 0
        self._last[i] = self._task.initial(self._actuators[i])
        return self._task.observation(self._last[i], self._targets[i])

    def reset(self, *, seed: int | list[int | None] | None = None, options: dict[str, Any] | None = None):
        if isinstance(seed, int):
            seeds: list[int | None] = [seed + i for i in range(self.num_envs)]
        elif seed is None:
            seeds = [None] * self.num_envs
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise InputError(f"{len(seeds)} seeds for {self.num_envs} environments")
        for i, s in enumerate(seeds):
            if s is not None or seed is None:
                self._rngs[i] = seeding.np_random(s)[0]
        obs = np.stack([self._reset_one(i) for i in range(self.num_envs)])
        self._pending_reset[:] = False
        return obs, {"target": self._targets.copy()}

    def step(self, actions: Any):
        u = self._task.action(actions, (self.num_envs, self._task.m))
        obs = np.zeros((self.num_envs,) + self.single_observation_space.shape)
        rewards = np.zeros(self.num_envs)
        terminated = np.zeros(self.num_envs, dtype=bool)
        truncated = np.zeros(self.num_envs, dtype=bool)
        errors: list[str | None] = [None] * self.num_envs
        live = [i for i in range(self.num_envs) if not self._pending_reset[i]]
        for i in range(self.num_envs):
            if self._pending_reset[i]:
                obs[i] = self._reset_one(i)
        if live:
            self._step_live(live, u, obs, rewards, terminated, truncated, errors)
        self._pending_reset = terminated | truncated
        info: dict[str, Any] = {"target": self._targets.copy()}
        if any(e is not None for e in errors):
            info["step_error"] = np.array(errors, dtype=object)
        return obs, rewards, terminated, truncated, info

    def _step_live(self, live, u, obs, rewards, terminated, truncated, errors) -> None:
        skip = self._task.frame_skip
        exc = np.repeat(u[live][:, None, :], skip, axis=1)
        acts = [self._actuators[i] for i in live]
        try:
            traj = rollout(acts, excitation=exc, outputs=_OUTPUTS, threads=self._threads)
        except StepError:
            # One instance failed: step each alone so the others' ticks stand as a single
            # environment's would, and the failed one ends as terminated.
            for k, i in enumerate(live):
                try:
                    one = self._actuators[i].rollout(exc[k], outputs=_OUTPUTS)
                except StepError as e:
                    errors[i] = str(e)
                    obs[i] = self._task.observation(self._last[i], self._targets[i])
                    rewards[i], terminated[i] = -self._task.failure_penalty, True
                    self._steps[i] += 1
                    continue
                self._finish(i, {k2: v[-1] for k2, v in one.items()}, u[i], obs, rewards, truncated)
            return
        for k, i in enumerate(live):
            self._finish(i, {name: v[k, -1] for name, v in traj.items()}, u[i], obs, rewards, truncated)

    def _finish(self, i, last, u, obs, rewards, truncated) -> None:
        self._last[i] = last
        self._steps[i] += 1
        obs[i] = self._task.observation(last, self._targets[i])
        rewards[i] = self._task.reward(last, self._targets[i], u)
        truncated[i] = self._steps[i] >= self._task.max_episode_steps

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        from ._render import arm_frame

        names = self._actuators[0].muscles
        return [arm_frame(self._last[i], self._targets[i], names, self._task.f_max) for i in range(self.num_envs)]

    @property
    def dt(self) -> float:
        """Simulated time a step covers, s (``frame_skip`` ticks)."""
        return self._task.frame_skip / self._actuators[0].rate_hz

    @property
    def actuators(self) -> list[Actuator]:
        """The stepped actuators, one per instance."""
        return self._actuators


def make_env(env_config: dict[str, Any] | None = None) -> ArmReachEnv:
    """A creator that needs no registry (RLlib's ``env`` may be this function)."""
    return ArmReachEnv(**(env_config or {}))


__all__ = [
    "ENVS",
    "ENV_ID",
    "FAST_ENV_ID",
    "ArmReachEnv",
    "ArmReachVectorEnv",
    "make_env",
    "register_envs",
]
