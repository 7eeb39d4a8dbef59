"""Calibrations of one subject on several sets of trials, each set on a Ray worker, checked
against the same calibrations run here one after the other (docs/python.md "Subjects, EMG and
calibration"):

    .venv/bin/python examples/ray_calibrate.py [EVALUATIONS]

A subject pickles as its TOML text and a calibration depends on nothing but its inputs and
its seed, so each worker's calibrated subject and result equal the local loop's, bit for bit.
The Ray cluster is a local one of 2 CPUs on 127.0.0.1, with Ray's token authentication and no
dashboard, as in docs/python.md "A sweep on Ray"; python/tests/test_subject.py runs
`on_ray` and `locally` with few evaluations.
"""

from __future__ import annotations

import os
import secrets
import sys

if "ray" not in sys.modules:  # Ray reads these when it is imported (docs/python.md)
    os.environ.setdefault("RAY_AUTH_MODE", "token")                 # Ray's token authentication,
    os.environ.setdefault("RAY_AUTH_TOKEN", secrets.token_hex(32))  # with this session's token

from pathlib import Path
from typing import Any

import ray

import muscle_actuator as ma

DATA = Path(__file__).resolve().parents[1] / "data" / "ceinms"
SUBJECT = DATA / "uncalibratedSubject.xml"
EXCITATIONS = DATA / "emgGenerator-16To34.xml"
DOFS = ["R_knee_fe"]
#: Each set: the trials one calibration is fitted to (folders of data/ceinms).
TRIAL_SETS = [
    ["_FastWalking_", "_CrossOvers1_"],
    ["_FastWalking1_", "_CrossOvers6_"],
    ["_FastWalking9_", "_CrossOvers7_"],
]

Result = tuple[ma.Subject, dict[str, Any]]


def calibrate_set(subject: ma.Subject, trials: list[str], seed: int, evaluations: int) -> Result:
    """One calibration of `subject` on `trials`, on one thread (a worker has one CPU)."""
    return ma.calibrate(
        subject,
        EXCITATIONS,
        [DATA / t for t in trials],
        DOFS,
        model="hill",
        seed=seed,
        evaluations=evaluations,
        threads=1,
    )


def on_ray(subject: ma.Subject, trial_sets: list[list[str]], seed: int, evaluations: int) -> list[Result]:
    """Every set's calibration as a Ray task (`ray.init` first)."""
    task = ray.remote(num_cpus=1)(calibrate_set)
    return ray.get([task.remote(subject, trials, seed, evaluations) for trials in trial_sets])


def locally(subject: ma.Subject, trial_sets: list[list[str]], seed: int, evaluations: int) -> list[Result]:
    """The same calibrations, one after the other, in this process."""
    return [calibrate_set(subject, trials, seed, evaluations) for trials in trial_sets]


def main(evaluations: int = 200, seed: int = 1) -> None:
    subject = ma.Subject.read(SUBJECT)
    ray.init(num_cpus=2, include_dashboard=False, _node_ip_address="127.0.0.1")
    try:
        remote = on_ray(subject, TRIAL_SETS, seed, evaluations)
    finally:
        ray.shutdown()
    local = locally(subject, TRIAL_SETS, seed, evaluations)
    assert remote == local, "a calibration on Ray differs from the local one"
    for trials, (calibrated, result) in zip(TRIAL_SETS, remote):
        print(
            f"{' + '.join(trials)}: mean 1 - R2 {result['cost']:.4f} from {result['start_cost']:.4f}"
            f" ({result['evaluations']} evaluations), strength of "
            + ", ".join(f"{k[len('strength.'):]} {v:.2f}" for k, v in result["parameters"].items()
                        if k.startswith("strength."))
        )


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
