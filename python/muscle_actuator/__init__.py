"""Muscle actuators from Python: Hill, Huxley Distribution-Moment and full Huxley models driving
any limb, the engine of the ``muscle_actuator`` ROS 2 node, bit for bit (docs/python.md).

- :class:`Actuator`: one limb, stepped many ticks per call; its state as named numpy arrays;
  ``get_state``/``set_state`` and pickling.
- :func:`rollout`: many actuators (each with its own parameters) over many ticks, on every core.
- :func:`simulate`, :func:`read_recording`, :func:`compare`: offline runs and recordings as
  arrays (:class:`Run`), and the ``compare`` command's figures.
- :class:`Subject`, :func:`predict`, :func:`calibrate`: a person's muscle–tendon units (a CEINMS
  subject) driven by a measured trial (:class:`Prediction`), and calibrated on trials' moments.
- :func:`emg_envelope`, :func:`neural_activation`: raw EMG to a normalised envelope, and
  Lloyd & Besier's activation of an excitation.
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
    Prediction,
    RecordingError,
    StepError,
    Subject,
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
    "Prediction",
    "RecordingError",
    "Run",
    "StepError",
    "Subject",
    "UnknownNameError",
    "TruncatedRecordingWarning",
    "calibrate",
    "compare",
    "emg_envelope",
    "neural_activation",
    "predict",
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


_Path = str | os.PathLike[str]


def predict(
    subject: Subject | _Path,
    excitations: _Path,
    trial: _Path,
    model: str = "huxley",
    dofs: str | Sequence[str] | None = None,
) -> Prediction:
    """``muscle_actuator predict``: the subject's units (a :class:`Subject` or its file) driven
    through the trial in the folder ``trial`` (``emg.txt``, ``lmt.txt``, ``<dof>Ma.txt``,
    ``<dof>Torque.txt``), each unit along its measured length under the excitation the map
    ``excitations`` (CEINMS's excitation generator) makes of the EMG; the units of ``dofs``
    (default: every degree of freedom of the trial). The numbers are those of ``predict --csv``
    and ``--muscles-csv``, bit for bit. Runs with the GIL released."""
    return _core._predict(subject, excitations, trial, model, dofs)


def calibrate(
    subject: Subject | _Path,
    excitations: _Path,
    trials: _Path | Sequence[_Path],
    dofs: str | Sequence[str],
    model: str = "huxley",
    seed: int = 1,
    evaluations: int = 1000,
    threads: int | None = None,
) -> tuple[Subject, dict[str, Any]]:
    """``muscle_actuator calibrate``: the subject's bounded parameters (C1, C2, shape factor,
    delay; per group of units strength, tendon slack and optimal fibre length multipliers)
    fitted by CMA-ES so that the units' moments of ``dofs`` match the trials' measured ones.

    Returns the calibrated :class:`Subject` (with its ``calibration`` record; ``to_toml()`` is
    the file ``calibrate --out`` writes) and a dict: ``cost`` and ``start_cost`` (mean of
    1 - R²), ``evaluations``, ``history`` (after each generation: evaluations so far, best cost)
    and ``parameters`` (name -> value). The same seed gives the same result on any number of
    ``threads`` (default: one per core). Runs with the GIL released."""
    return _core._calibrate(subject, excitations, trials, dofs, model, seed, evaluations, threads)


def emg_envelope(
    raw: Any,
    rate_hz: float,
    *,
    remove_mean: bool = True,
    band_pass: tuple[float, float] | None = (20.0, 450.0),
    band_pass_order: int = 4,
    low_pass_hz: float = 6.0,
    low_pass_order: int = 4,
    phase: str = "zero-phase",
    normalisation: str | float | None = "signal-peak",
) -> np.ndarray:
    """The normalised linear envelope of raw EMG sampled at ``rate_hz``: the mean removed, a
    Butterworth band-pass (``band_pass`` Hz, None for none), full-wave rectification, a
    Butterworth low-pass (``low_pass_hz``), then division by the normaliser: ``"signal-peak"``
    (the largest value of the envelope(s) given), a number (an MVC envelope's peak) or None.
    ``phase`` is ``"zero-phase"`` (forward and backward, no lag: ``scipy.signal.sosfiltfilt``)
    or ``"causal"`` (one forward pass, as online). ``raw`` is one signal ``(samples,)`` or
    several ``(signals, samples)``, all divided by their common peak; the result has its shape.
    The defaults are the crate's (``muscle_actuator_core::emg::envelope``)."""
    return _core._emg_envelope(
        raw,
        rate_hz,
        remove_mean,
        None if band_pass is None else (float(band_pass[0]), float(band_pass[1])),
        band_pass_order,
        low_pass_hz,
        low_pass_order,
        phase,
        normalisation,
    )


def neural_activation(
    excitation: Any, c1: float, c2: float, shape_factor: float, delay_samples: int = 0
) -> np.ndarray:
    """Lloyd & Besier's activation of an excitation (a normalised envelope, clamped to [0, 1]),
    one value per sample, from rest: the recursion ``u[k] = α e[k-d] - β1 u[k-1] - β2 u[k-2]``
    (``β1 = C1 + C2``, ``β2 = C1 C2``, ``α = 1 + β1 + β2``: a constant excitation gives itself),
    |C1|, |C2| < 1, a delay of ``delay_samples`` samples, then ``a = (exp(A u) - 1)/(exp(A) - 1)``
    with A = ``shape_factor`` in [-3, 3] (the line a = u at A = 0). C1 and C2 belong to the
    excitation's sample period. ``excitation`` is ``(samples,)`` or ``(signals, samples)``."""
    return _core._neural_activation(excitation, c1, c2, shape_factor, delay_samples)


register_envs()
