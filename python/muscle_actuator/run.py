"""A run as arrays: what ``simulate`` computes and what a recording holds."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._core import UnknownNameError


@dataclass(frozen=True)
class Run:
    """A run: the state after every tick (the first row is the initial state).

    ``arrays`` maps each output to an array: a ``MuscleState`` field (``"force"``) to
    ``(ticks + 1, muscles)``, ``"joint." + field`` (``"joint.position"``) to ``(ticks + 1,
    joints)``, ``"stiffness_matrix"`` to ``(ticks + 1, joints, joints)``. ``run["force"]`` is
    ``run.arrays["force"]``. SI units (docs/ros-interface.md lists them).
    """

    scenario: str
    model: str
    rate_hz: float
    muscles: list[str]
    joints: list[str]
    #: Per muscle, the indices of the joints it spans.
    muscle_joints: list[list[int]]
    #: Time at the end of each tick, s (0 for the initial state).
    time: np.ndarray
    arrays: dict[str, np.ndarray] = field(repr=False)

    @classmethod
    def _from_dict(cls, d: dict[str, Any]) -> "Run":
        return cls(
            scenario=d["scenario"],
            model=d["model"],
            rate_hz=d["rate_hz"],
            muscles=list(d["muscles"]),
            joints=list(d["joints"]),
            muscle_joints=[list(j) for j in d["muscle_joints"]],
            time=d["time"],
            arrays=dict(d["arrays"]),
        )

    def __getitem__(self, output: str) -> np.ndarray:
        try:
            return self.arrays[output]
        except KeyError:
            raise UnknownNameError(
                f"unknown output {output[:64]!r}: expected one of {', '.join(self.arrays)}"
            ) from None

    def muscle(self, name: str) -> dict[str, np.ndarray]:
        """Every per-muscle output of muscle ``name``, one value per tick."""
        if name not in self.muscles:
            raise UnknownNameError(f"unknown muscle {name[:64]!r}: expected one of {', '.join(self.muscles)}")
        i = self.muscles.index(name)
        return {k: v[:, i] for k, v in self.arrays.items() if not k.startswith("joint.") and v.ndim == 2}

    def to_pandas(self) -> "Any":
        """The run as ``simulate --csv`` writes it: one row per tick and muscle, columns
        ``time``, ``name``, the ``MuscleState`` fields, then ``J.field`` for each joint J (NaN
        on the rows of muscles that do not span J). Needs pandas."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Run.to_pandas needs pandas: pip install pandas") from e
        from . import JOINT_FIELDS, MUSCLE_FIELDS

        n, m = len(self.time), len(self.muscles)
        cols: dict[str, Any] = {
            "time": np.repeat(self.time, m),
            "name": np.tile(np.array(self.muscles, dtype=object), n),
        }
        for f in MUSCLE_FIELDS:
            cols[f] = self.arrays[f].reshape(n * m)
        for j, joint in enumerate(self.joints):
            spans = np.array([j in self.muscle_joints[i] for i in range(m)])
            mask = np.tile(spans, n)
            for f in JOINT_FIELDS:
                v = np.repeat(self.arrays["joint." + f][:, j], m)
                cols[f"{joint}.{f}"] = np.where(mask, v, np.nan)
        return pd.DataFrame(cols)
