"""Muscle actuators from Python: Hill, Huxley Distribution-Moment and full Huxley models driving
any limb, the engine of the ``muscle_actuator`` ROS 2 node, bit for bit (docs/python.md).

- :class:`Actuator`: one limb, stepped many ticks per call; its state as named numpy arrays;
  ``get_state``/``set_state`` and pickling.
- :func:`rollout`: many actuators (each with its own parameters) over many ticks, on every core.
- :func:`simulate`, :func:`read_recording`, :func:`compare`: offline runs and recordings as
  arrays (:class:`Run`), and the ``compare`` command's figures.
- :mod:`muscle_actuator.gym`: Gymnasium environments (``muscle_actuator/ArmReach-v0``),
  registered with Gymnasium on import of this package when Gymnasium is installed.
- :class:`Error` (a ``ValueError``) and its kinds: :class:`ConfigError`, :class:`InputError`,
  :class:`StepError`, :class:`RecordingError`, :class:`UnknownNameError` (also a ``KeyError``),
  :class:`FileNotFound` (also a ``FileNotFoundError``).
"""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Mapping, Sequence

import numpy as np

from . import _core
from ._core import (
    Actuator,
    ActuatorState,
    ConfigError,
    Error,
    FileNotFound,
    InputError,
    RecordingError,
    StepError,
    UnknownNameError,
)
from ._registration import register_envs
from .run import Run

__all__ = [
    "Actuator",
    "ActuatorState",
    "ConfigError",
    "Error",
    "FileNotFound",
    "InputError",
    "RecordingError",
    "Run",
    "StepError",
    "UnknownNameError",
    "TruncatedRecordingWarning",
    "compare",
    "read_recording",
    "rollout",
    "simulate",
    "MUSCLE_FIELDS",
    "JOINT_FIELDS",
]
__version__: str = _core.__version__

#: The per-muscle outputs (the ``MuscleState`` fields), in message order.
MUSCLE_FIELDS: tuple[str, ...] = tuple(Actuator.muscle_fields)
#: The per-joint outputs, in message order; as output names they carry ``joint.`` before them.
JOINT_FIELDS: tuple[str, ...] = tuple(Actuator.joint_fields)


class TruncatedRecordingWarning(UserWarning):
    """A recording cut by a crash was read up to the cut (as ``replay`` and ``export`` do)."""


def rollout(
    config: str | os.PathLike[str] | Mapping[str, Any] | Sequence[Actuator] | None,
    model: str = "huxley",
    excitation: Any = None,
    external_torque: Any = None,
    *,
    rate_hz: float = 1000.0,
    energy_model: str | None = None,
    substeps: int | None = None,
    overrides: Sequence[Mapping[str, Any]] | None = None,
    outputs: Sequence[str] | None = None,
    threads: int | None = None,
    tolerance: float | None = None,
) -> dict[str, np.ndarray]:
    """Steps B independent actuators over T ticks on ``threads`` threads (default: one per core)
    with the GIL released, and returns the chosen outputs after each tick as arrays
    ``(B, T, muscles)``, ``(B, T, joints)`` (``joint.*``) or ``(B, T, joints, joints)``
    (``stiffness_matrix``).

    ``config`` is a configuration (built-in name, path or dict; B new actuators are built, each
    with its own ``overrides[b]``, dotted keys such as ``"muscle.flexor.k_t"``), or a list of
    :class:`Actuator` objects, advanced in place from their current state. ``excitation`` is
    ``(B, T, muscles)``, ``external_torque`` ``(B, T, joints)`` or None (held as it is). Each
    actuator is stepped alone by one thread: the results equal stepping each by itself, bit for
    bit, in any thread count. ``tolerance`` is the adaptive sub-steps' relative tolerance (the
    override ``"stepper.tolerance"`` for every instance; default: the configuration's, else the
    model's).
    """
    if excitation is None:
        raise InputError("excitation is required: an array (instances, ticks, muscles)")
    if isinstance(config, (list, tuple)) and all(isinstance(a, Actuator) for a in config) and config:
        if (
            overrides is not None
            or energy_model is not None
            or substeps is not None
            or tolerance is not None
        ):
            raise ConfigError(
                "overrides, energy_model, substeps and tolerance apply to new actuators only"
            )
        return _core._rollout_actuators(
            list(config), excitation, external_torque, outputs=outputs, threads=threads
        )
    return _core._rollout_new(
        config,
        model,
        excitation,
        external_torque,
        rate_hz=rate_hz,
        energy_model=energy_model,
        substeps=substeps,
        overrides=list(overrides) if overrides is not None else None,
        outputs=list(outputs) if outputs is not None else None,
        threads=threads,
        tolerance=tolerance,
    )


def simulate(
    scenario: str | os.PathLike[str],
    model: str = "huxley",
    config: str | os.PathLike[str] | Mapping[str, Any] | None = None,
    *,
    rate_hz: float = 1000.0,
    substeps: int | None = None,
    energy_model: str | None = None,
    out: str | os.PathLike[str] | None = None,
    tolerance: float | None = None,
) -> Run:
    """``muscle_actuator simulate``: a built-in scenario (``pulse``, ``energy-10hz``,
    ``energy-100hz``) or a scenario file, run offline; recorded to ``out`` (MCAP) if given. The
    numbers are those of ``simulate --csv``, bit for bit. ``tolerance`` sets the configuration's
    ``stepper.tolerance`` (the adaptive sub-steps' relative tolerance)."""
    return Run._from_dict(
        _core._simulate(scenario, model, config, rate_hz, substeps, energy_model, out, tolerance)
    )


def read_recording(path: str | os.PathLike[str]) -> Run:
    """A recording (of the node or of ``simulate --out``) as ``export`` reads it: the same strict
    reader and refusals as ``replay``; a file cut by a crash is read up to the cut with a
    :class:`TruncatedRecordingWarning`."""
    d = _core._read_recording(path)
    if d.get("warning"):
        warnings.warn(d["warning"], TruncatedRecordingWarning, stacklevel=2)
    return Run._from_dict(d)


def compare(
    a: str | os.PathLike[str], b: str | os.PathLike[str], *, plot: str | os.PathLike[str] | None = None
) -> dict[str, Any]:
    """``muscle_actuator compare A B --json`` as a dict: the compared span, per-signal RMS and
    largest differences, peaks and rise times, and each muscle's energies. ``plot`` writes the
    overlay of the muscles' forces (PNG and SVG, drawn with matplotlib) as ``--plot`` does."""
    text, notes = _core._compare(a, b, plot)
    for w in notes:
        warnings.warn(w, TruncatedRecordingWarning, stacklevel=2)
    if plot is not None:
        from ._compare_plot import overlay

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", TruncatedRecordingWarning)
            overlay(read_recording(a), read_recording(b), plot)
    return json.loads(text)


register_envs()
