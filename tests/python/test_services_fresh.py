"""The first call of a fresh client is answered, and at once: no retry, and Fast DDS with its
stock settings (fresh_clients.py runs without the tests' 100 ms heartbeat profile).

A client that calls right after `wait_for_service` races the node's discovery of its two
endpoints: its request can reach the node before the node knows its request writer, and the
answer can be written before the node knows its reply reader. The node asks for such a request
at once when the writer matches, and holds such an answer until the reader matches
(vendor/rustdds/PATCHED.md); `/diagnostics` counts the answers held and dropped."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from diagnostic_msgs.msg import DiagnosticArray

from helpers import NodeProcess

CLIENTS = Path(__file__).resolve().parent / "fresh_clients.py"

# A first call is answered within this: half of Fast DDS's heartbeat period (3 s), the wait of a
# request the node did not take and did not ask for again. What remains is discovery and the
# node's start, which on a loaded 2-core machine took up to 0.81 s once in 20 cold starts; on an
# idle one, under 5 ms.
ANSWER_S = 1.5


def stock_env():
    env = dict(os.environ)
    env.pop("FASTDDS_DEFAULT_PROFILES_FILE", None)
    env.pop("FASTRTPS_DEFAULT_PROFILES_FILE", None)
    return env


def start_clients(fqn, count, services="reset"):
    return subprocess.Popen(
        [sys.executable, str(CLIENTS), fqn, "--count", str(count), "--services", services],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=stock_env(),
    )


def results(proc, timeout):
    out, err = proc.communicate(timeout=timeout)
    assert proc.returncode == 0, err[-2000:]
    return json.loads(out.strip().splitlines()[-1])


def unanswered(calls):
    return [c for c in calls if not (c["found"] and c["answered"] and c["success"])]


def services_status(peer, node):
    """The node's next `/diagnostics` services status, as {key: value}."""
    inbox = peer.subscribe(DiagnosticArray, "/diagnostics")
    name = f"{node.fqn}: services"
    arr = inbox.wait(lambda a: any(s.name == name for s in a.status), timeout=10.0,
                     what=f"/diagnostics of {node.fqn}")
    return {kv.key: kv.value for s in arr.status if s.name == name for kv in s.values}


@pytest.fixture(scope="module")
def lockstep(node_factory):
    return node_factory(
        "/t_fresh", "-p", "clock:=lockstep", "-p", "model:=hill", "-p", "record:=false",
    )


@pytest.mark.timeout(600)
def test_a_hundred_fresh_clients_are_each_answered_once(peer, lockstep):
    peer.wait_for_node("muscle_actuator", "/t_fresh")
    calls = results(start_clients(lockstep.fqn, 100, "reset,step"), timeout=540)
    assert len(calls) == 200
    assert unanswered(calls) == [], unanswered(calls)[:5]
    seconds = sorted(c["seconds"] for c in calls)
    print(f"\n200 first calls, seconds to the answer: median {seconds[100]:.4f}, "
          f"slowest {[round(s, 4) for s in seconds[-5:]]}")
    # A request the node received before it knew the client's writer is asked for again at
    # once, not at the client's next heartbeat (3 s).
    assert seconds[-1] <= ANSWER_S, seconds[-5:]
    # Every answer that had to wait for its client's reader went out when it matched.
    services = services_status(peer, lockstep)
    print(f"\n{lockstep.fqn} services: {services}")
    assert services["replies_dropped"] == "0", services
    assert services["replies_held_sent"] == services["replies_held"], services


@pytest.mark.timeout(600)
def test_a_client_started_with_the_node_is_answered_at_once():
    slowest = []
    for k in range(20):
        node = NodeProcess(f"/t_cold{k}", ["-p", "record:=false"])
        # The client first, so that it calls the moment it sees the node: while the node is
        # still discovering it.
        clients = start_clients(node.fqn, 1)
        assert clients.stderr.readline().strip() == "waiting"
        node.start()
        try:
            calls = results(clients, timeout=60)
        finally:
            node.stop()
        assert unanswered(calls) == [], (k, calls, node.output()[-2000:])
        slowest.append(calls[0]["seconds"])
    print(f"\ncold starts, seconds to the first answer: {[round(s, 4) for s in sorted(slowest)]}")
    assert max(slowest) <= ANSWER_S, sorted(slowest)
