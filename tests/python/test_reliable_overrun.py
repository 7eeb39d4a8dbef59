"""A reliable keep-last reader that falls behind (docs/ros-interface.md#subscribers-that-fall-behind):
against `clock:=sim` flat out, publishing ~/state every tick (about 10^5 a second), an rclpy
subscriber (reliable, keep last 10) keeps receiving the newest states, thinned, in every half
second, and never falls further behind than that."""

import time

from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from rosgraph_msgs.msg import Clock
from muscle_actuator_msgs.msg import ActuatorState

from helpers import reliable

RUN_S = 10.0
WINDOW_S = 0.5
CLOCK_QOS = QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, history=HistoryPolicy.KEEP_LAST, depth=1)


def ns(stamp):
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def test_reliable_subscriber_keeps_receiving_the_newest_states(peer, node_factory):
    n = node_factory("/t_overrun", "-p", "clock:=sim", "-p", "model:=hill", "-p", "record:=false")
    clock = peer.subscribe(Clock, "/clock", CLOCK_QOS)
    states = peer.subscribe(ActuatorState, n.topic("~/state"), reliable(10))
    peer.wait_matched_sub(states)
    states.wait(timeout=10.0, what="a first state")
    t0 = time.monotonic()
    time.sleep(RUN_S - WINDOW_S)
    # The node's time half a second before the end: the last state must be newer.
    behind = ns(clock.wait(timeout=5.0, since=time.monotonic(), what="/clock").clock)
    time.sleep(WINDOW_S)
    got = states.timed(since=t0)
    windows = [0] * int(RUN_S / WINDOW_S)
    for t, _m in got:
        k = int((t - t0) / WINDOW_S)
        if k < len(windows):
            windows[k] += 1
    ticks = [m.tick for _t, m in got]
    print(f"states per {WINDOW_S} s window: {windows}; ticks {ticks[0]}..{ticks[-1]}")
    assert all(c > 0 for c in windows), f"no state in some half second: {windows}"
    assert all(a < b for a, b in zip(ticks, ticks[1:])), "states out of order or repeated"
    # Flat out: far more ticks than states (thinned, not every one).
    assert ticks[-1] - ticks[0] > 10 * len(ticks), (ticks[0], ticks[-1], len(ticks))
    assert ns(got[-1][1].header.stamp) > behind, "the last state is older than the node's time 0.5 s before"
    assert n.alive(), n.output()
