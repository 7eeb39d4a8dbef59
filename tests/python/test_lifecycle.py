"""Start-up errors are one clear line; SIGINT and SIGTERM stop the node cleanly: exit 0 within a
second."""

import signal
import subprocess
import time

import pytest

from helpers import NodeProcess, Watch


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_cleanly_within_a_second(peer, sig):
    n = NodeProcess(f"/t_life_{sig.name.lower()}", ["-p", "publish_rate_hz:=50.0"])
    n.start()
    Watch(peer, n, diagnostics=False)  # up and publishing
    rc = n.stop(sig)
    out = n.output()
    assert rc == 0, out[-2000:]
    assert n.stop_seconds < 1.0, f"took {n.stop_seconds:.2f} s to stop"
    assert "panicked" not in out
    assert "stopped after" in out


@pytest.mark.parametrize(
    "args,word",
    [
        (["--bogus"], "--bogus"),
        (["--ros-args", "-r", "__ns:=/bad-ns"], "__ns"),
        (["--ros-args", "--log-level", "loud"], "loud"),
    ],
)
def test_bad_arguments_fail_with_one_clear_line(args, word):
    p = subprocess.run(
        [NodeProcess.binary(), "node", *args], capture_output=True, text=True, timeout=20
    )
    assert p.returncode != 0
    err = (p.stderr + p.stdout).strip()
    assert word in err, err
    assert "panicked" not in err
    assert len(err.splitlines()) <= 3, err


def test_invalid_domain_is_refused():
    p = subprocess.run(
        [NodeProcess.binary(), "node"],
        capture_output=True,
        text=True,
        timeout=20,
        env={**__import__("os").environ, "ROS_DOMAIN_ID": "999"},
    )
    assert p.returncode != 0
    assert "ROS_DOMAIN_ID" in p.stderr + p.stdout
