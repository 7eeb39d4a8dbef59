"""docs/python.md's examples run as they stand, in order, in one namespace (a notebook)."""

from __future__ import annotations

import re
import sys

import pytest

from conftest import ROOT


def blocks() -> list[str]:
    text = (ROOT / "docs/python.md").read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_the_walk_through_has_its_six_blocks():
    assert len(blocks()) == 6


def test_the_walk_through_runs(tmp_path, monkeypatch):
    pytest.importorskip("ray")
    pytest.importorskip("gymnasium")
    pytest.importorskip("matplotlib")
    import ray

    # Functions defined in the blocks live in this namespace; Ray's workers get them by value.
    monkeypatch.chdir(tmp_path)
    real_init = ray.init
    monkeypatch.setattr(ray, "init", lambda **kw: real_init(_node_ip_address="127.0.0.1", **kw))
    namespace: dict = {"__name__": "__main__"}
    for k, code in enumerate(blocks()):
        exec(compile(code, f"docs/python.md block {k + 1}", "exec"), namespace)
    assert (tmp_path / "pulse.png").stat().st_size > 10_000
    assert (tmp_path / "dm.mcap").exists()
