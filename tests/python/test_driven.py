"""Driven joints (docs/configuration.md, docs/ros-interface.md): a robot simulator owns the
elbow and plays its motion on ~/joint_states_in; the node steps the muscles for that motion and
publishes their net torque on ~/joint_efforts. Driven in lockstep, the efforts match `simulate`
of the same motion offline; bad joint states are refused and a silent simulator is reported."""

import csv
import math
import subprocess
import time

import pytest
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray

from helpers import ROOT, NodeProcess, reliable, wait_until
from test_clock import matched, reset, step

AMPLITUDE, FREQUENCY, OFFSET = 0.5, 1.0, 0.1
TICKS = 300

SCENARIO = f"""
name = "driven-sine"
duration = {TICKS / 1000.0}
attachment = "driven"
[[input]]
signal = "joint_angle"
joint = "elbow"
kind = "sine"
amplitude = {AMPLITUDE}
frequency = {FREQUENCY}
offset = {OFFSET}
[[input]]
signal = "excitation"
muscle = "flexor"
kind = "constant"
value = 0.2
[[input]]
signal = "excitation"
muscle = "extensor"
kind = "constant"
value = 0.1
"""


def motion(t):
    """The sine schedule's value and derivative, as `simulate` evaluates them."""
    w = 2.0 * math.pi * FREQUENCY
    return OFFSET + AMPLITUDE * math.sin(2.0 * math.pi * FREQUENCY * t + 0.0), AMPLITUDE * w * math.cos(w * t + 0.0)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("driven")
    text = (ROOT / "crates" / "core" / "configs" / "elbow.toml").read_text()
    cfg = d / "driven_elbow.toml"
    # The elbow starts where the motion does (the sine's offset), as `simulate` starts it.
    cfg.write_text(text.replace("initial_angle = 0.0", f"initial_angle = {OFFSET}\ndriven = true", 1))
    scn = d / "scenario.toml"
    scn.write_text(SCENARIO)
    return cfg, scn, d


@pytest.fixture(scope="module")
def driven(node_factory, files):
    cfg = files[0]
    return node_factory(
        "/t_driven", "-p", "clock:=lockstep", "-p", "model:=hill", "-p", f"config:={cfg}",
        "-p", "record:=false", "-p", "joint_state_timeout_ticks:=50",
    )


def joint_state(name, position, velocity):
    m = JointState()
    m.name = list(name)
    m.position = [float(x) for x in position]
    m.velocity = [float(x) for x in velocity]
    return m


def warm_up(peer, node, pub, angle):
    """The joint-state writer, like the command writer, may reach the node late until matched:
    publish the elbow at rest at `angle` and step one tick until a state shows it."""
    for _ in range(200):
        pub.publish(joint_state(["elbow"], [angle], [0.0]))
        if abs(step(peer, node, 1).state.position[0] - angle) < 1e-12:
            return
        time.sleep(0.02)
    raise AssertionError("the node never showed the warm-up joint state")


def test_efforts_match_simulate_of_the_same_motion(peer, driven, files):
    cfg, scn, d = files
    out = d / "offline.csv"
    r = subprocess.run(
        [NodeProcess.binary(), "simulate", str(scn), "--config", str(cfg), "--model", "hill",
         "--csv", str(out)],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    with open(out) as f:
        offline = {}
        for row in csv.DictReader(f):
            offline[round(float(row["time"]) * 1000)] = float(row["elbow.torque"])

    efforts = peer.subscribe(Float64MultiArray, driven.topic("~/joint_efforts"), reliable(1000))
    peer.wait_matched_sub(efforts)
    states_pub = peer.publisher(JointState, driven.topic("~/joint_states_in"))
    matched(peer, driven)
    warm_up(peer, driven, states_pub, 0.25)
    reset(peer, driven)
    peer.activation_acked(driven.topic("~/activation"), flexor=0.2, extensor=0.1)
    online = {}
    for k in range(TICKS):
        angle, velocity = motion(k / 1000.0)
        # Other joints of the simulator are ignored.
        states_pub.publish(joint_state(["wrist", "elbow"], [9.0, angle], [0.0, velocity]))
        peer.acked(states_pub)  # at the node before the step (docs/time.md)
        r = step(peer, driven, 1)
        assert r.success and r.tick == k + 1, (r.message, r.tick)
        online[r.tick] = r.state.torque[0]
    worst = max(abs(online[k] - offline[k]) / max(abs(offline[k]), 1e-3) for k in range(1, TICKS + 1))
    assert worst < 1e-9, worst
    assert max(abs(offline[k]) for k in online) > 1.0  # the muscles do pull
    # ~/joint_efforts carries the same torques (in lockstep every tick is published).
    wait_until(lambda: len(efforts.msgs()) >= TICKS, 10.0, what="the efforts")
    last = [list(m.data) for m in efforts.msgs()[-TICKS:]]
    assert last == [[online[k]] for k in range(1, TICKS + 1)]


def last_problem(diag):
    for d in reversed(diag.msgs()):
        for st in d.status:
            for kv in st.values:
                if kv.key == "last_problem":
                    return kv.value
    return ""


def status_of(diag, name_part):
    for d in reversed(diag.msgs()):
        for st in d.status:
            if name_part in st.name:
                return st
    return None


def test_bad_and_missing_joint_states_are_refused_and_a_silent_simulator_is_reported(peer, driven):
    diag = peer.subscribe(DiagnosticArray, "/diagnostics")
    peer.wait_matched_sub(diag)
    pub = peer.publisher(JointState, driven.topic("~/joint_states_in"))
    pub.publish(joint_state(["elbow"], [0.2], [0.0]))
    wait_until(lambda: step(peer, driven, 1).state.position[0] == 0.2, 10.0, what="at rest")
    before = step(peer, driven, 1).state.position[0]
    pub.publish(joint_state(["elbow"], [float("nan")], [0.0]))
    wait_until(lambda: "joint state rejected" in last_problem(diag), 10.0, what="the NaN refused")
    # Refused whole: the motion in force goes on (here: at rest where the last one left it).
    assert step(peer, driven, 1).state.position[0] == before
    pub.publish(joint_state(["knee"], [0.3], [0.0]))
    wait_until(lambda: "names none of the driven joints" in last_problem(diag), 10.0,
               what="the unmatched joint state reported")
    # No joint state for more than joint_state_timeout_ticks (50): a warning.
    assert step(peer, driven, 80).success
    wait_until(
        lambda: (st := status_of(diag, "tick loop")) is not None
        and "no JointState for" in st.message,
        10.0,
        what="the stale warning",
    )
    st = status_of(diag, "tick loop")
    assert st.level == DiagnosticStatus_WARN
    pub.publish(joint_state(["elbow"], [0.0], [0.0]))
    wait_until(lambda: abs(step(peer, driven, 1).state.position[0]) < 0.01, 10.0,
               what="the joint state after the silence")


DiagnosticStatus_WARN = b"\x01"


def test_driven_node_run_replays_bit_for_bit(peer, node_factory, files, tmp_path):
    """A driven run recorded by the node holds the motion as the tick loop applied it (and the
    motion it started from): `replay` gives every recorded state back bit for bit, the
    extrapolation between joint states included."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    cfg = files[0]
    rec_dir = tmp_path / "runs"
    n = node_factory(
        "/t_driven_rec", "-p", "clock:=lockstep", "-p", "model:=huxley", "-p", f"config:={cfg}",
        "-p", f"record_dir:={rec_dir}",
    )
    pub = peer.publisher(JointState, n.topic("~/joint_states_in"))
    matched(peer, n)
    # Until the first joint state shows, the node steps with the elbow at rest where it starts.
    warm_up(peer, n, pub, 0.3)
    sent = 0
    for k in range(40):
        peer.activation(n.topic("~/activation"), flexor=0.1 * (k % 5), extensor=0.2)
        if k % 3 != 2:  # every third step gets no joint state: the motion is extrapolated
            angle, velocity = motion(k / 100.0)
            pub.publish(joint_state(["elbow"], [angle], [velocity]))
            sent += 1
        assert step(peer, n, 1 + k % 4).success
    assert n.stop() == 0, n.output()
    (path,) = rec_dir.glob("*.mcap")
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        meta = {m.name: m.metadata for m in reader.iter_metadata()}["muscle_actuator"]
        msgs = [(ch.topic, d) for _, ch, m, d in reader.iter_decoded_messages()]
    applied = [d for (t, d) in msgs if t.endswith("/applied/joint_motion")]
    received = [d for (t, d) in msgs if t.endswith("/joint_states_in")]
    states = [d for (t, d) in msgs if t.endswith("/state")]
    # Every joint state received was applied (the warm-up ones included), each at one tick.
    assert len(received) >= sent + 1 and len(applied) == len(received), (len(received), len(applied))
    assert [list(a.name) for a in applied] == [["elbow"]] * len(applied)
    assert float(meta["initial_joint_motion"].split()[0]) == OFFSET
    r = subprocess.run(
        [NodeProcess.binary(), "replay", str(path), "--out", str(tmp_path / "again.mcap")],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    assert f"{len(states)} of {len(states)} recorded states reproduced bit for bit" in r.stderr, r.stderr
