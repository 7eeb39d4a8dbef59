"""Recordings as arrays: `read_recording` of a node recording and of `simulate --out` returns
what `export` writes, through the same strict reader (same refusals, same truncation warning);
`compare` returns the `compare --json` figures."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import ROOT, assert_bits_equal, cli_path, read_csv


def assert_run_is_export(cli, run: ma.Run, path: Path) -> None:
    header, rows = read_csv(cli("export", str(path), "--csv", "-").stdout)
    m = len(run.muscles)
    assert len(rows) == len(run.time) * m
    assert_bits_equal(np.array([float(r[0]) for r in rows[::m]]), run.time, "time")
    for c, field in enumerate(header[2:], start=2):
        if field in ma.MUSCLE_FIELDS:
            want = np.array([float(r[c]) for r in rows])
            assert_bits_equal(run[field].reshape(-1), want, field)


def test_read_recording_of_simulate_out_is_export_and_simulate(cli, tmp_path):
    out = tmp_path / "dm.mcap"
    run = ma.simulate("pulse", model="huxley", out=out)
    back = ma.read_recording(out)
    assert back.model == "huxley" and back.muscles == run.muscles and back.rate_hz == 1000.0
    for k in run.arrays:
        assert_bits_equal(back[k], run[k], k)
    assert_run_is_export(cli, back, out)


@pytest.fixture(scope="module")
def node_recording(tmp_path_factory) -> Path:
    """A recording of the node itself: started on the embedded defaults, stopped by SIGINT."""
    d = tmp_path_factory.mktemp("node_runs")
    env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST", ROS_DOMAIN_ID=os.environ.get("ROS_DOMAIN_ID", "57"))
    p = subprocess.Popen(
        [str(cli_path()), "node", "--ros-args", "-r", "__ns:=/pytest_pkg", "-p", f"record_dir:={d}"],
        cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
    )
    try:
        time.sleep(2.0)
    finally:
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=30)
    files = sorted(d.glob("*.mcap"))
    assert p.returncode == 0 and files, out[-2000:]
    return files[0]


def test_read_recording_of_a_node_recording_is_export(cli, node_recording):
    run = ma.read_recording(node_recording)
    assert run.muscles == ["flexor", "extensor"] and run.joints == ["elbow"]
    assert len(run.time) > 100  # a state per tick at 1 kHz for about two seconds
    assert np.all(np.diff(run.time) > 0)
    assert_run_is_export(cli, run, node_recording)


def test_a_cut_recording_warns_and_a_damaged_one_is_refused_as_replay_refuses(cli, tmp_path, node_recording):
    data = node_recording.read_bytes()
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(data[: len(data) * 2 // 3])
    with pytest.warns(ma.TruncatedRecordingWarning):
        part = ma.read_recording(cut)
    assert 0 < len(part.time) < len(ma.read_recording(node_recording).time)
    junk = tmp_path / "junk.mcap"
    junk.write_bytes(b"\x89MCAP0\r\n" + b"\x00" * 64)
    with pytest.raises(ValueError) as e:
        ma.read_recording(junk)
    p = cli("replay", str(junk), "--out", str(tmp_path / "r.mcap"), check=False)
    assert p.returncode != 0 and str(e.value) in p.stderr
    with pytest.raises(ValueError, match="does not exist|No such file"):
        ma.read_recording(tmp_path / "none.mcap")


def test_compare_returns_the_cli_json(cli, tmp_path):
    a, b = tmp_path / "hill.mcap", tmp_path / "dm.mcap"
    ma.simulate("pulse", model="hill", out=a)
    ma.simulate("pulse", model="huxley", out=b)
    got = ma.compare(a, b)
    want = json.loads(cli("compare", str(a), str(b), "--json").stdout)
    assert got == want
    assert got["model_a"] == "hill" and got["model_b"] == "huxley" and got["samples"] == 3001
    force = [s for s in got["signals"] if s["signal"].endswith(".force")][0]
    assert force["rms_diff"] > 0.0


def test_simulate_refuses_to_write_over_an_input(tmp_path):
    sc = tmp_path / "s.toml"
    sc.write_text((ROOT / "scenarios/elbow_cocontraction_ramp.toml").read_text())
    before = sc.read_bytes()
    with pytest.raises(ValueError, match="would overwrite .* which this command reads"):
        ma.simulate(sc, model="hill", out=sc)
    assert sc.read_bytes() == before
