"""Oversized input costs no memory and silences nothing: a flood of commands with a 1 MB muscle
name, a 70,000-character parameter value, a FIFO as configuration file, and hostile start-up
arguments (a 10,000-character node name, a 120 kB `-p` value, a parameters file nested 100,000
levels deep). Each is refused briefly, and the node goes on answering."""

import os
import time

import pytest
from rclpy.parameter import Parameter

from helpers import NodeProcess, Watch

NS = "/t_big"
MB = 1 << 20


def rss_mb(pid):
    for line in open(f"/proc/{pid}/status"):
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS")


@pytest.fixture(scope="module")
def node(node_factory, tmp_path_factory):
    rec = tmp_path_factory.mktemp("big") / "runs"
    return node_factory(NS, "-p", f"record_dir:={rec}")


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node, rosout=True)


def test_a_flood_of_megabyte_names_costs_no_memory(peer, node, watch):
    watch.diagnostics(timeout=10.0)
    before = rss_mb(node.proc.pid)
    topic = node.topic("~/activation")
    t0 = time.monotonic()
    sent = 0
    samples = []  # (time, RSS)
    refused = 0
    while time.monotonic() - t0 < 8.0:
        try:
            peer.raw_activation(topic, ["m" * MB], [0.5])
            sent += 1
        except Exception:  # Fast DDS refuses a send while its buffers are full
            refused += 1
            time.sleep(0.001)
        if (sent + refused) % 50 == 0:
            samples.append((time.monotonic() - t0, rss_mb(node.proc.pid)))
    wall = time.monotonic() - t0
    time.sleep(1.5)
    samples.append((time.monotonic() - t0, rss_mb(node.proc.pid)))
    peak = max(r for _, r in samples)
    mid = max(r for t, r in samples if t <= wall / 2)
    print(f"{sent} commands with a 1 MB name in {wall:.1f} s ({sent * MB / wall / 1e6:.0f} MB/s): "
          f"node RSS {before:.0f} MB before, {peak:.0f} MB at most ({refused} sends refused by "
          f"the publisher)")
    assert sent >= 200, f"only {sent} sent"
    # Bounded: what DDS holds for one reader (up to 128 samples in reassembly and 64 in its
    # cache: ~200 MB of 1 MB samples) and the recorder's 32 MiB; reached early, then flat.
    assert peak - before < 320, f"RSS grew from {before:.0f} MB to {peak:.0f} MB"
    assert peak - mid < 50, f"RSS still growing: {mid:.0f} MB half-way, {peak:.0f} MB at the end"
    # /diagnostics kept its 1 Hz through the flood, and quotes the name briefly.
    times = [t for (t, a) in watch.diag.timed(t0)
             if any(s.hardware_id == node.fqn for s in a.status)]
    gaps = [b - a for a, b in zip([t0] + times, times)]
    assert times and max(gaps) < 3.0, f"/diagnostics gaps {gaps}"
    inputs = watch.diagnostics()["inputs"]
    # Most never reach the node (a reliable reader keeps the last samples, not all of them).
    assert int(inputs["rejected_unknown_name"]) > 0
    problem = inputs.get("last_problem", "")
    assert "(1048576 bytes)" in problem and len(problem) < 300, problem[:400]
    lines = [m.msg for m in watch.rosout.msgs() if "unknown name" in m.msg]
    assert lines and max(len(x) for x in lines) < 1100, [len(x) for x in lines]
    # And the node still takes a valid command.
    watch.activation(flexor=0.4, extensor=0.1)


def test_a_huge_parameter_value_is_refused_briefly(peer, node, watch):
    client = peer.param_client(node)
    for name, value in [("model", "h" * 70_000), ("config", "/" + "c" * 70_000)]:
        resp = peer.await_future(client.set_parameters([Parameter(name, value=value)]))
        r = resp.results[0]
        assert not r.successful and "too long" in r.reason and len(r.reason) < 300, r.reason[:400]
    # The same client still gets answers.
    resp = peer.await_future(client.get_parameters(["model"]))
    assert resp.values[0].string_value == "huxley"


def test_a_fifo_as_configuration_is_refused_at_once(peer, node, watch, tmp_path):
    fifo = tmp_path / "config.fifo"
    os.mkfifo(fifo)
    client = peer.param_client(node)
    t0 = time.monotonic()
    resp = peer.await_future(client.set_parameters([Parameter("config", value=str(fifo))]))
    took = time.monotonic() - t0
    r = resp.results[0]
    assert not r.successful and "regular file" in r.reason, r.reason
    assert took < 5.0, f"{took:.1f} s"
    for dev in ("/dev/zero", "/dev/urandom"):
        resp = peer.await_future(client.set_parameters([Parameter("config", value=dev)]))
        assert not resp.results[0].successful and "regular file" in resp.results[0].reason
    # Commands and diagnostics go on.
    watch.activation(flexor=0.2, extensor=0.2)
    watch.diagnostics(timeout=5.0)


@pytest.mark.parametrize(
    "args, rule",
    [
        (["-r", "__node:=" + "n" * 10_000], "at most 255"),
        (["-r", "__ns:=/" + "n" * 10_000], "at most 245"),
        (["-p", "model:=" + "m" * 120_000], "too long"),
        (["--params-file", "DEEP"], "nested deeper than 64"),
        (["--params-file", "/dev/zero"], "regular file"),
    ],
)
def test_hostile_start_up_arguments_are_one_short_error(args, rule, tmp_path):
    if "DEEP" in args:
        deep = tmp_path / "deep.yaml"
        deep.write_text("/**:\n  ros__parameters:\n    x: " + "[" * 100_000 + "]" * 100_000 + "\n")
        args = [str(deep) if a == "DEEP" else a for a in args]
    n = NodeProcess("/t_big_bad", args)
    t0 = time.monotonic()
    n.start()
    rc = n.proc.wait(timeout=20)
    took = time.monotonic() - t0
    out = n.output().strip()
    assert rc != 0 and rule in out, out[:400]
    assert len(out) < 600 and "panicked" not in out, out[:600]
    assert took < 5.0, f"{took:.1f} s"
