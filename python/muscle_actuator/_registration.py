"""The package's Gymnasium environments, registered on ``import muscle_actuator`` when Gymnasium
is installed (as MyoSuite's are on ``import myosuite``). Gymnasium ≥ 1.0 loads no plugins by
entry point; ``gym.make("muscle_actuator:muscle_actuator/ArmReach-v0")`` imports this package
first by Gymnasium's ``module:id`` form.

Whether Gymnasium is there is looked up without importing it; the registration names the
classes by string, so ``muscle_actuator.gym`` is imported only when an environment is made."""

from __future__ import annotations

import importlib.util

#: The environments: id -> (entry point, vector entry point, keyword arguments).
ENVS: dict[str, tuple[str, str, dict[str, object]]] = {
    "muscle_actuator/ArmReach-v0": (
        "muscle_actuator.gym:ArmReachEnv",
        "muscle_actuator.gym:ArmReachVectorEnv",
        {},
    ),
    # The same task (10 ms a step) with the Hill model on equilibrium fibres and rigid tendons,
    # 2 ms ticks and tolerance 1e-3 (muscle_actuator.gym's docstring says what that costs).
    "muscle_actuator/ArmReachFast-v0": (
        "muscle_actuator.gym:ArmReachEnv",
        "muscle_actuator.gym:ArmReachVectorEnv",
        {
            "model": "hill",
            "fibre": "equilibrium",
            "tendon": "rigid",
            "rate_hz": 500.0,
            "frame_skip": 5,
            "tolerance": 1e-3,
        },
    ),
}


def register_envs() -> None:
    """Registers :data:`ENVS` with Gymnasium (once); does nothing without Gymnasium."""
    if importlib.util.find_spec("gymnasium") is None:
        return
    import gymnasium

    for env_id, (entry_point, vector_entry_point, kwargs) in ENVS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(
                id=env_id,
                entry_point=entry_point,
                vector_entry_point=vector_entry_point,
                kwargs=kwargs,
            )
