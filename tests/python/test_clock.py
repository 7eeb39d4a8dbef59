"""Simulated time (docs/time.md): with `clock:=sim` the node is the graph's clock, faster than
the wall clock, and an rclpy node with use_sim_time follows its /clock; with `clock:=lockstep` it
advances only on `~/step`, and a closed-loop rclpy controller gets the same trajectory every
time."""

import math
import time

import pytest
from std_msgs.msg import Int64
from muscle_actuator_msgs.msg import ActuatorState
from muscle_actuator_msgs.srv import Step
from std_srvs.srv import Trigger

from helpers import SERVICE_TIMEOUT, reliable, wait_until
from spun import SpunNode

RATE = 1000.0


def ns(stamp):
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def tick_stamp(tick, rate=RATE):
    return round(tick * 1e9 / rate)


@pytest.fixture(scope="module")
def sim_node(node_factory):
    return node_factory(
        "/t_sim", "-p", "clock:=sim", "-p", "model:=hill", "-p", "publish_rate_hz:=100.0",
        "-p", "record:=false",
    )


def test_sim_is_the_graphs_clock_and_runs_ahead_of_the_wall(peer, sim_node):
    follower = SpunNode("t_sim_follower", use_sim_time=True)
    try:
        wait_until(lambda: follower.now_ns() > 0, 15.0, what="the follower's clock to start")
        a_sim, a_wall = follower.now_ns(), time.monotonic()
        wait_until(lambda: time.monotonic() - a_wall > 1.0, 2.0)
        b_sim, b_wall = follower.now_ns(), time.monotonic()
        # As fast as the steps go: far more than one simulated second per wall second.
        assert (b_sim - a_sim) / 1e9 > 5.0 * (b_wall - a_wall), (b_sim - a_sim, b_wall - a_wall)
    finally:
        follower.close()
    # ~/state is stamped with simulated time: tick / rate, exactly.
    states = peer.subscribe(ActuatorState, sim_node.topic("~/state"), reliable(100))
    peer.wait_matched_sub(states)
    s = states.wait(lambda m: m.tick > 0, timeout=10.0, what="a state")
    assert ns(s.header.stamp) == tick_stamp(s.tick)
    assert s.tick % 10 == 0  # 100 Hz of simulated time at 1 kHz


def test_real_time_factor_paces_simulated_time(peer, node_factory):
    n = node_factory(
        "/t_rtf", "-p", "clock:=sim", "-p", "model:=hill", "-p", "real_time_factor:=4.0",
        "-p", "record:=false", "-p", "publish_rate_hz:=100.0",
    )
    states = peer.subscribe(ActuatorState, n.topic("~/state"), reliable(100))
    peer.wait_matched_sub(states)
    states.wait(timeout=10.0, what="a state")
    t0 = time.monotonic()
    first = states.wait(lambda m: True, timeout=5.0, since=t0)
    wait_until(lambda: time.monotonic() - t0 > 2.0, 3.0)
    last = states.msgs()[-1]
    simulated = (ns(last.header.stamp) - ns(first.header.stamp)) / 1e9
    wall = time.monotonic() - t0
    # Four simulated seconds per wall second, within what a loaded 2-core VM allows.
    assert 2.5 * wall < simulated < 4.6 * wall, (simulated, wall)


# A script in simulated time: (s, excitations) laid out ahead, stamped with the time each is for.
SCRIPT = [
    (4.0, {"flexor": 0.6, "extensor": 0.1}),
    (4.25, {"flexor": 0.0, "extensor": 0.8}),
    (4.5005, {"flexor": 0.3, "extensor": 0.3}),  # between two ticks: the next one
    (4.9, {"flexor": 1.0}),
]
SCRIPT_END = 5.5


def scripted_sim_run(peer, node_factory, rec_dir, name):
    """A `clock:=sim` node at real time, fed SCRIPT (stamped ahead) right after start; the
    recording's states and applied inputs up to SCRIPT_END, raw bytes by tick."""
    from mcap.reader import make_reader
    from muscle_actuator_msgs.msg import ActivationCommand

    n = node_factory(
        name, "-p", "clock:=sim", "-p", "real_time_factor:=1.0", "-p", "model:=huxley",
        "-p", "publish_rate_hz:=100.0", "-p", f"record_dir:={rec_dir}",
    )
    states = peer.subscribe(ActuatorState, n.topic("~/state"), reliable(100))
    peer.wait_matched_sub(states)
    pub = peer.publisher(ActivationCommand, n.topic("~/activation"))
    for t, u in SCRIPT:
        m = ActivationCommand()
        m.header.stamp.sec, m.header.stamp.nanosec = int(t), round((t - int(t)) * 1e9)
        m.muscle, m.excitation = list(u), [float(x) for x in u.values()]
        pub.publish(m)
    sent_at = ns(states.wait(timeout=10.0, what="a state").header.stamp)
    # The script went out well before its first time (else this run proves nothing).
    assert sent_at < (SCRIPT[0][0] - 1.0) * 1e9, sent_at
    states.wait(lambda m: ns(m.header.stamp) >= SCRIPT_END * 1e9, timeout=20.0, what="the end")
    assert n.stop() == 0, n.output()
    (path,) = rec_dir.glob("*.mcap")
    got = {"state": {}, "applied": [], "path": path}
    with open(path, "rb") as f:
        for _, ch, msg in make_reader(f).iter_messages():
            # States and inputs as applied are logged at their tick's stamp.
            assert msg.log_time == msg.publish_time or not ch.topic.endswith(("/state", "/applied/activation"))
            if msg.log_time > SCRIPT_END * 1e9:
                continue
            if ch.topic.endswith("/state"):
                got["state"][msg.log_time] = bytes(msg.data)
            elif ch.topic.endswith("/applied/activation"):
                got["applied"].append((msg.log_time, bytes(msg.data)))
    return got


def test_sim_runs_of_the_same_scripted_inputs_record_the_same_bits(peer, node_factory, tmp_path):
    """Inputs stamped ahead of a simulated clock wait for their time, so a script laid out in
    simulated time gives the same recording, bit for bit, however the two runs were scheduled
    on the wall clock."""
    a = scripted_sim_run(peer, node_factory, tmp_path / "a", "/t_script_a")
    b = scripted_sim_run(peer, node_factory, tmp_path / "b", "/t_script_b")
    # Each input applied at the first tick stamped at or after its time.
    want = [round(math.ceil(t * 1000 - 1e-9) * 1e6) for t, _ in SCRIPT]
    assert [t for t, _ in a["applied"]] == want, [t for t, _ in a["applied"]]
    assert a["applied"] == b["applied"]
    assert len(a["state"]) >= SCRIPT_END * 100 - 1, len(a["state"])
    assert a["state"] == b["state"]
    # And replay gives a sim run back bit for bit (its whole length).
    import subprocess

    from helpers import NodeProcess

    r = subprocess.run(
        [NodeProcess.binary(), "replay", str(a["path"]), "--out", str(tmp_path / "again.mcap")],
        capture_output=True, text=True,
    )
    assert r.returncode == 0 and "reproduced bit for bit" in r.stderr, r.stderr


@pytest.fixture(scope="module")
def lockstep(node_factory):
    return node_factory(
        "/t_lock", "-p", "clock:=lockstep", "-p", "model:=hill", "-p", "record:=false",
    )


def reset(peer, node):
    """`~/reset`, asked once: a first call is answered, however soon after the node appears
    (test_services_fresh.py)."""
    r = peer.call(Trigger, node.topic("~/reset"), Trigger.Request(), timeout=SERVICE_TIMEOUT)
    assert r.success, r.message
    return r


def step(peer, node, ticks):
    req = Step.Request()
    req.ticks = ticks
    return peer.call(Step, node.topic("~/step"), req, timeout=SERVICE_TIMEOUT)


def matched(peer, node):
    """Until the node has matched our activation writer both ways, a command can reach it
    late, after a heartbeat repairs it, and after a later step request (a discovery race of any
    DDS pair, not of the stepping): command and step until a state shows the command."""
    topic = node.topic("~/activation")
    for _ in range(200):
        peer.activation(topic, flexor=0.5, extensor=0.5)
        r = step(peer, node, 1)
        if all(m.excitation == 0.5 for m in r.state.muscles):
            return
        time.sleep(0.02)
    raise AssertionError("the node never showed the warm-up command")


def test_lockstep_stands_still_until_stepped(peer, lockstep):
    first = step(peer, lockstep, 1)
    assert first.success, first.message
    time.sleep(0.5)
    r = step(peer, lockstep, 3)
    assert r.success and r.tick == first.tick + 3, (first.tick, r.tick)
    assert ns(r.state.header.stamp) == tick_stamp(r.tick)
    assert r.state.tick == r.tick


def test_inputs_before_a_step_take_effect_at_its_first_tick(peer, lockstep):
    topic = lockstep.topic("~/activation")
    matched(peer, lockstep)
    for k in range(40):
        u = 0.1 + 0.8 * (k % 2)
        peer.activation_acked(topic, flexor=u, extensor=1.0 - u)
        r = step(peer, lockstep, 1)
        assert r.success, r.message
        got = {m.name: m.excitation for m in r.state.muscles}
        assert got == {"flexor": u, "extensor": 1.0 - u}, (k, got)


def test_step_requests_that_cannot_be_done_get_a_reason(peer, lockstep, node_factory):
    for ticks in (0, -5, 10**12):
        r = step(peer, lockstep, ticks)
        assert not r.success and "ticks" in r.message, r.message
    # One step at a time: a second request while a long one runs is refused at once.
    client = peer.node.create_client(Step, lockstep.topic("~/step"))
    assert client.wait_for_service(timeout_sec=10.0)
    long_req, short_req = Step.Request(), Step.Request()
    long_req.ticks, short_req.ticks = 3_000_000, 1
    before = step(peer, lockstep, 1).tick
    slow = client.call_async(long_req)
    time.sleep(0.2)
    quick = client.call_async(short_req)
    wait_until(quick.done, SERVICE_TIMEOUT, what="the refusal")
    assert not quick.result().success and "running" in quick.result().message
    wait_until(slow.done, 120.0, what="the long step")
    assert slow.result().success and slow.result().tick == before + 3_000_000
    # A node on the wall clock says what ~/step needs.
    wall = node_factory("/t_lock_wall", "-p", "model:=hill", "-p", "record:=false")
    r = step(peer, wall, 1)
    assert not r.success and "clock:=lockstep" in r.message, r.message


def test_step_topic_advances_fire_and_forget(peer, lockstep):
    states = peer.subscribe(ActuatorState, lockstep.topic("~/state"), reliable(1000))
    peer.wait_matched_sub(states)
    before = step(peer, lockstep, 1).tick
    pub = peer.publisher(Int64, lockstep.topic("~/step"))
    pub.publish(Int64(data=25))
    pub.publish(Int64(data=-3))  # refused (logged)
    pub.publish(Int64(data=5))
    states.wait(lambda m: m.tick == before + 30, timeout=10.0, what="30 more ticks")
    time.sleep(0.3)
    assert step(peer, lockstep, 1).tick == before + 31


def pid_run(peer, node, steps=300, ticks_per_step=10, target=0.4):
    """A PID controller closing the loop through ~/step every 10 ms of simulated time:
    co-contraction 0.5 plus antagonistic excitation from the angle error; returns the
    (tick, angle, velocity) trajectory."""
    matched(peer, node)
    reset(peer, node)
    topic = node.topic("~/activation")
    kp, ki, kd, c0 = 1.0, 1.0, 0.1, 0.5
    trajectory = []
    angle, velocity, integral = 0.0, 0.0, 0.0
    for _ in range(steps):
        e = target - angle
        integral = max(-0.3, min(0.3, integral + ki * e * ticks_per_step / RATE))
        drive = max(-0.5, min(0.5, kp * e + integral - kd * velocity))
        peer.activation_acked(topic, flexor=c0 + max(drive, 0.0), extensor=c0 + max(-drive, 0.0))
        r = step(peer, node, ticks_per_step)
        assert r.success, r.message
        angle, velocity = r.state.position[0], r.state.velocity[0]
        trajectory.append((r.tick, angle, velocity))
    return trajectory


def test_lockstep_closed_loop_reaches_the_target_the_same_way_twice(peer, lockstep):
    a = pid_run(peer, lockstep)
    b = pid_run(peer, lockstep)
    assert a == b  # bit for bit: every input took effect at the same tick
    assert a[-1][0] == 3000
    assert abs(a[0][1]) < 0.05  # it starts at rest, away from the target
    final = [angle for (_, angle, _) in a[-30:]]
    assert all(abs(x - 0.4) < 0.03 for x in final), final


def test_lockstep_recording_has_simulated_time_and_replays_bit_for_bit(peer, node_factory, tmp_path):
    import subprocess

    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    from helpers import NodeProcess

    rec_dir = tmp_path / "runs"
    n = node_factory(
        "/t_lock_rec", "-p", "clock:=lockstep", "-p", "model:=huxley",
        "-p", f"record_dir:={rec_dir}",
    )
    matched(peer, n)
    for k in range(30):
        peer.activation_acked(n.topic("~/activation"), flexor=0.1 * (k % 7), extensor=0.3)
        assert step(peer, n, 5 + k).success
    last = step(peer, n, 1)
    assert n.stop() == 0, n.output()
    (path,) = rec_dir.glob("*.mcap")
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        meta = {m.name: m.metadata for m in reader.iter_metadata()}["muscle_actuator"]
        msgs = [(ch.topic, m.log_time, d) for _, ch, m, d in reader.iter_decoded_messages()]
    assert meta["time_base"] == "simulated" and '"clock":"lockstep"' in meta["parameters_json"]
    # One clock: simulated time, from zero to the last tick (log times and stamps alike).
    end = tick_stamp(last.tick)
    assert all(0 <= lt <= end for (_, lt, _) in msgs), max(lt for (_, lt, _) in msgs)
    states = [d for (t, _, d) in msgs if t.endswith("/state")]
    assert states[-1].tick == last.tick
    assert all(ns(s.header.stamp) == tick_stamp(s.tick) for s in states)
    r = subprocess.run(
        [NodeProcess.binary(), "replay", str(path), "--out", str(tmp_path / "again.mcap")],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    assert f"{len(states)} of {len(states)} recorded states reproduced bit for bit" in r.stderr, r.stderr
