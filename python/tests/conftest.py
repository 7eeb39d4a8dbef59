"""Shared fixtures of the Python package's tests: the repository, the command-line binary (the
same crate, built by `cargo test`; MUSCLE_ACTUATOR_BIN overrides it) and a CSV reader that keeps
every bit (the CLI prints shortest round-trip floats)."""

from __future__ import annotations

import csv
import io
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def cli_path() -> Path:
    env = os.environ.get("MUSCLE_ACTUATOR_BIN")
    if env:
        return Path(env)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "debug" / "muscle_actuator"


@pytest.fixture(scope="session")
def cli():
    path = cli_path()
    if not path.exists():
        pytest.fail(f"no command-line binary at {path}: run `cargo build` first")

    def run(*args: str, check: bool = True) -> subprocess.CompletedProcess:
        p = subprocess.run([str(path), *args], capture_output=True, text=True, cwd=ROOT, timeout=600)
        if check and p.returncode != 0:
            raise AssertionError(f"{args}: exit {p.returncode}: {p.stderr[-2000:]}")
        return p

    return run


def read_csv(text: str) -> tuple[list[str], list[list[str]]]:
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], rows[1:]


def assert_bits_equal(a: np.ndarray, b: np.ndarray, what: str) -> None:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    assert a.shape == b.shape, f"{what}: shapes {a.shape} vs {b.shape}"
    diff = a.view(np.uint64) != b.view(np.uint64)
    if diff.any():
        k = np.argwhere(diff)[0]
        raise AssertionError(f"{what}: first difference at {tuple(k)}: {a[tuple(k)]!r} vs {b[tuple(k)]!r}")
