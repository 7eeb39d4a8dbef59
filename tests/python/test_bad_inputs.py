"""Bad input gets a clear answer and loses nothing (docs/robustness.md): unknown names, mismatched
lengths, NaN/inf are rejected whole and counted; excitations outside [0, 1] are clamped and
reported; the last valid command stays in force; the node keeps its rate meanwhile."""

import math
import re
import time

import pytest

from helpers import Watch, muscle, wait_until

NS = "/t_bad"


@pytest.fixture(scope="module")
def node(node_factory):
    return node_factory(NS, "-p", "model:=hill", "-p", "publish_rate_hz:=100.0")


@pytest.fixture(scope="module")
def watch(peer, node):
    w = Watch(peer, node, rosout=True)
    w.activation(flexor=0.3, extensor=0.1)
    w.load(0.5)
    return w


def counters(watch):
    return watch.diagnostics()["inputs"]


def wait_counter(watch, key, above, timeout=10.0):
    """Waits for the diagnostics counter `key` to exceed `above`; returns the inputs block."""
    def check():
        d = counters(watch)
        return d if int(d[key]) > above else None
    return wait_until(check, timeout, what=f"diagnostics {key} > {above}")


def in_force(watch, flexor, extensor, torque):
    s = watch.next_state()
    assert muscle(s, "flexor").excitation == flexor
    assert muscle(s, "extensor").excitation == extensor
    assert s.external_torque[0] == torque
    return s


ACTIVATION_CASES = [
    ("unknown_name", ["flexor", "biceps"], [0.9, 0.9]),
    ("length_mismatch", ["flexor", "extensor"], [0.9]),
    ("non_finite", ["flexor"], [math.nan]),
    ("non_finite", ["extensor"], [math.inf]),
    ("non_finite", ["flexor", "extensor"], [0.9, -math.inf]),
    ("duplicate_name", ["flexor", "flexor"], [0.9, 0.8]),
    ("empty", [], []),
]


@pytest.mark.parametrize("kind,names,values", ACTIVATION_CASES)
def test_bad_activation_is_rejected_whole(peer, node, watch, kind, names, values):
    before = counters(watch)
    peer.raw_activation(node.topic("~/activation"), names, values)
    after = wait_counter(watch, f"rejected_{kind}", int(before[f"rejected_{kind}"]))
    assert int(after["activation_rejected"]) > int(before["activation_rejected"])
    assert after["_level"] == 1  # WARN in the period with a rejection
    assert after["last_problem"].startswith("activation command rejected")
    # Nothing of it applied (not even the valid part): the last valid command stays.
    in_force(watch, 0.3, 0.1, 0.5)


@pytest.mark.parametrize(
    "kind,joints,torques",
    [
        ("unknown_name", ["knee"], [1.0]),
        ("length_mismatch", ["elbow"], [1.0, 2.0]),
        ("non_finite", ["elbow"], [math.nan]),
    ],
)
def test_bad_load_is_rejected_whole(peer, node, watch, kind, joints, torques):
    before = counters(watch)
    peer.load(node.topic("~/external_load"), joints, torques)
    after = wait_counter(watch, f"rejected_{kind}", int(before[f"rejected_{kind}"]))
    assert int(after["load_rejected"]) > int(before["load_rejected"])
    assert after["last_problem"].startswith("external load rejected")
    in_force(watch, 0.3, 0.1, 0.5)


def test_rejections_are_reported_on_rosout(watch):
    m = watch.rosout.wait(
        lambda m: "rejected" in m.msg and "biceps" in m.msg, timeout=10.0,
        what="a /rosout warning naming the unknown muscle",
    )
    assert m.level == 30


def test_out_of_range_excitation_is_clamped_and_reported(peer, node, watch):
    before = counters(watch)
    watch.activation(flexor=1.7, extensor=-0.2)  # waits until the clamped values are in force
    after = wait_counter(watch, "clamped_values", int(before["clamped_values"]) + 1)
    assert int(after["clamped_commands"]) > int(before["clamped_commands"])
    assert int(after["activation_rejected"]) == int(before["activation_rejected"])
    watch.rosout.wait(lambda m: "clamped" in m.msg, timeout=10.0, what="a /rosout note on clamping")
    in_force(watch, 1.0, 0.0, 0.5)
    watch.activation(flexor=0.3, extensor=0.1)


def test_node_keeps_its_rate_under_a_flood_of_bad_input(peer, node, watch):
    topic = node.topic("~/activation")
    before = counters(watch)
    t0 = time.monotonic()
    first = watch.next_state()
    sent = 0
    while time.monotonic() - t0 < 2.0:
        peer.raw_activation(topic, ["flexor"], [math.nan])
        sent += 1
        time.sleep(0.002)
    last = watch.next_state()
    wall = time.monotonic() - t0
    # Ticks keep coming at 1 kHz (the loop catches up any late tick) and states at 100 Hz.
    tick_rate = (last.tick - first.tick) / wall
    assert 800 <= tick_rate <= 1200, f"tick rate {tick_rate:.0f} Hz while flooded"
    states = [m for (t, m) in watch.state.timed(t0)]
    assert len(states) / wall >= 70, f"{len(states)} states in {wall:.1f} s"
    after = wait_counter(watch, "rejected_non_finite", int(before["rejected_non_finite"]) + sent // 2)
    assert int(after["activation_rejected"]) - int(before["activation_rejected"]) >= sent // 2
    in_force(watch, 0.3, 0.1, 0.5)
    diag = watch.diagnostics()["tick loop"]
    assert int(diag["step_failures"]) == 0


def test_non_finite_state_resets_the_joint_and_keeps_running(peer, node, watch):
    """A finite but absurd load drives the state out of range: the node resets the joint, says
    so on /rosout and /diagnostics, never publishes NaN, and keeps ticking."""
    before = int(watch.diagnostics()["tick loop"]["step_failures"])
    t0 = time.monotonic()
    topic = node.topic("~/external_load")

    def blown_up():
        peer.load(topic, ["elbow"], [1e308])
        d = watch.diagnostics()["tick loop"]
        return d if int(d["step_failures"]) > before else None

    diag = wait_until(blown_up, 20.0, interval=0.2, what="a failed step and reset")
    assert "a step failed" in diag["_message"]
    # The log names the failed tick and why it failed.
    watch.rosout.wait(lambda m: re.search(r"tick \d+ failed \((the state became non-finite|"
                                          r"the implicit solver did not converge)", m.msg)
                      and m.level == 40, timeout=10.0,
                      what="an ERROR on /rosout about the reset")
    states = [m for (t, m) in watch.state.timed(t0)]
    from helpers import finite_state
    assert states and all(finite_state(s) for s in states)
    # It keeps running: a valid command afterwards takes effect and the joint moves again.
    watch.load(1.0)
    s = watch.states_after(time.monotonic(), 0.3)[-1]
    assert s.position[0] > 0.0 and s.external_torque[0] == 1.0
    assert int(watch.diagnostics()["tick loop"]["step_failures"]) == int(diag["step_failures"])
