"""Type stubs of the extension module (python/src/*.rs)."""

import os
from typing import Any, Mapping, Sequence, final

import numpy as np
import numpy.typing as npt

_Config = str | os.PathLike[str] | Mapping[str, Any] | None
_Inputs = npt.ArrayLike | Mapping[str, float] | None
_Path = str | os.PathLike[str]

__all__ = [
    "Actuator",
    "ActuatorState",
    "ConfigError",
    "Error",
    "FileNotFound",
    "InputError",
    "Prediction",
    "RecordingError",
    "StepError",
    "Subject",
    "UnknownNameError",
    "__version__",
    "_calibrate",
    "_compare",
    "_emg_envelope",
    "_emg_envelope_defaults",
    "_neural_activation",
    "_predict",
    "_read_recording",
    "_rollout_actuators",
    "_rollout_new",
    "_simulate",
]

__version__: str

class Error(ValueError):
    """Every error of muscle_actuator (a ValueError)."""

class ConfigError(Error):
    """A bad configuration, override, stepping, rate or thread count; a bad scenario file."""

class InputError(Error):
    """Bad inputs (shape, type or value); nothing was changed."""

class StepError(Error, RuntimeError):
    """A tick failed; ``tick``, ``reason`` and, in a batch, ``instance`` say which and why."""

    tick: int
    reason: str
    instance: int | None

class RecordingError(Error):
    """A recording that cannot be read (damaged, or not of this program)."""

class UnknownNameError(Error, KeyError):
    """An unknown model, energy model, muscle, joint, output or scenario name."""

class FileNotFound(Error, FileNotFoundError):
    """A configuration, scenario or recording file that does not exist."""

@final
class ActuatorState:
    """A saved state (``Actuator.get_state``); pickles."""

    @property
    def tick(self) -> int: ...
    @staticmethod
    def _from_bytes(bytes: bytes) -> ActuatorState: ...

@final
class Actuator:
    """A limb of joints and muscles stepped at a fixed tick (docs/python.md)."""

    muscle_fields: list[str]
    joint_fields: list[str]
    def __new__(
        cls,
        config: _Config = None,
        model: str = "huxley",
        rate_hz: float = 1000.0,
        *,
        energy_model: str | None = None,
        substeps: int | None = None,
        overrides: Mapping[str, Any] | None = None,
        tolerance: float | None = None,
    ) -> Actuator: ...
    @property
    def muscles(self) -> list[str]: ...
    @property
    def joints(self) -> list[str]: ...
    @property
    def driven_joints(self) -> list[str]: ...
    @property
    def model(self) -> str: ...
    @property
    def rate_hz(self) -> float: ...
    @property
    def tick(self) -> int: ...
    @property
    def time(self) -> float: ...
    @property
    def config(self) -> dict[str, Any]: ...
    @property
    def muscle_state(self) -> dict[str, np.ndarray]: ...
    @property
    def joint_state(self) -> dict[str, np.ndarray]: ...
    @property
    def stiffness_matrix(self) -> np.ndarray: ...
    @property
    def joint_efforts(self) -> np.ndarray: ...
    def step(self, excitation: _Inputs = None, external_torque: _Inputs = None, ticks: int = 1) -> None: ...
    def rollout(
        self,
        excitation: npt.ArrayLike,
        external_torque: npt.ArrayLike | None = None,
        outputs: Sequence[str] | None = None,
    ) -> dict[str, np.ndarray]: ...
    def reset(self) -> None: ...
    def observe(self, outputs: Sequence[str] | None = None) -> dict[str, np.ndarray]: ...
    def set_joint_motion(self, joint: str | int, angle: float, velocity: float = 0.0) -> None: ...
    def get_state(self) -> ActuatorState: ...
    def set_state(self, state: ActuatorState) -> None: ...
    def copy(self) -> Actuator: ...
    def __copy__(self) -> Actuator: ...
    def __deepcopy__(self, _memo: Any) -> Actuator: ...
    @staticmethod
    def _from_bytes(bytes: bytes) -> Actuator: ...

def _rollout_new(
    config: _Config,
    model: str,
    excitation: npt.ArrayLike,
    external_torque: npt.ArrayLike | None = None,
    *,
    rate_hz: float = 1000.0,
    energy_model: str | None = None,
    substeps: int | None = None,
    overrides: list[Mapping[str, Any]] | None = None,
    outputs: list[str] | None = None,
    threads: int | None = None,
    tolerance: float | None = None,
) -> dict[str, np.ndarray]: ...
def _rollout_actuators(
    actuators: list[Actuator],
    excitation: npt.ArrayLike,
    external_torque: npt.ArrayLike | None = None,
    *,
    outputs: Sequence[str] | None = None,
    threads: int | None = None,
) -> dict[str, np.ndarray]: ...
def _simulate(
    scenario: str | os.PathLike[str],
    model: str = "huxley",
    config: _Config = None,
    rate_hz: float = 1000.0,
    substeps: int | None = None,
    energy_model: str | None = None,
    out: str | os.PathLike[str] | None = None,
    tolerance: float | None = None,
) -> dict[str, Any]: ...
def _read_recording(path: str | os.PathLike[str]) -> dict[str, Any]: ...
def _compare(
    a: str | os.PathLike[str], b: str | os.PathLike[str], plot: str | os.PathLike[str] | None = None
) -> tuple[str, list[str]]: ...

@final
class Subject:
    """A subject's muscle-tendon units: CEINMS's XML or the project's TOML (docs/emg.md)."""

    @staticmethod
    def read(path: _Path) -> Subject: ...
    @staticmethod
    def from_toml(text: str) -> Subject: ...
    def to_toml(self) -> str: ...
    @property
    def id(self) -> str: ...
    @property
    def units(self) -> list[str]: ...
    @property
    def dofs(self) -> dict[str, list[str]]: ...
    @property
    def calibration(self) -> dict[str, Any] | None: ...
    @property
    def bounds(self) -> dict[str, list[float]]: ...
    def unit_params(self, name: str) -> dict[str, Any]: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Prediction:
    """A subject driven through a trial, at the trial's kinematic samples."""

    @property
    def trial(self) -> str: ...
    @property
    def model(self) -> str: ...
    @property
    def clamped_excitations(self) -> int: ...
    @property
    def held_lengths(self) -> int: ...
    @property
    def time(self) -> np.ndarray: ...
    @property
    def dofs(self) -> list[str]: ...
    @property
    def units(self) -> list[str]: ...
    @property
    def moment(self) -> dict[str, np.ndarray]: ...
    @property
    def measured(self) -> dict[str, np.ndarray]: ...
    @property
    def force(self) -> np.ndarray: ...
    @property
    def activation(self) -> np.ndarray: ...
    @property
    def fibre_length(self) -> np.ndarray: ...
    def ratings(self) -> dict[str, dict[str, float]]: ...
    def to_pandas(self) -> tuple[Any, Any]: ...
    @staticmethod
    def _from_state(state: Any) -> Prediction: ...

def _predict(
    subject: Subject | _Path,
    excitations: _Path,
    trial: _Path,
    model: str = "huxley",
    dofs: str | Sequence[str] | None = None,
) -> Prediction: ...
def _calibrate(
    subject: Subject | _Path,
    excitations: _Path,
    trials: _Path | Sequence[_Path],
    dofs: str | Sequence[str],
    model: str,
    seed: int,
    evaluations: int,
    threads: int | None,
) -> tuple[Subject, dict[str, Any]]: ...
def _emg_envelope(
    raw: npt.ArrayLike,
    rate_hz: float,
    remove_mean: bool,
    band_pass: tuple[float, float] | None,
    band_pass_order: int,
    low_pass_hz: float,
    low_pass_order: int,
    phase: str,
    normalisation: str | float | None,
) -> np.ndarray: ...
def _emg_envelope_defaults() -> dict[str, Any]: ...
def _neural_activation(
    excitation: npt.ArrayLike, c1: float, c2: float, shape_factor: float, delay_samples: int = 0
) -> np.ndarray: ...
