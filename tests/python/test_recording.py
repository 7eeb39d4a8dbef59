"""Recordings read with the tools users have: `mcap` + `mcap-ros2-support` and `rosbags`
(AnyReader, with only the schemas embedded in the file). Files from `simulate` (against the CSV
of the same run) and from the node (against what rclpy received live); a SIGKILLed recording
keeps what was flushed up to about a second before the kill, and `recover` makes it a complete
file the summary-based reader opens; a recording directory that cannot
be written leaves the node running and reporting."""

import csv
import os
import signal
import subprocess
import tempfile
import time
from pathlib import Path

import pytest
from diagnostic_msgs.msg import DiagnosticArray
from mcap.reader import make_reader
from mcap.stream_reader import StreamReader
from mcap.records import Channel, Chunk, Message
from mcap_ros2.decoder import DecoderFactory
from muscle_actuator_msgs.msg import ActuatorState, MuscleState
from rosbags.highlevel import AnyReader
from sensor_msgs.msg import JointState

from helpers import NodeProcess, doctor, wait_until

# The field lists of the message definitions: a muscle's numbers, and the per-joint arrays and
# the stiffness matrix of a state.
MUSCLE_FIELDS = [f for f, t in MuscleState.get_fields_and_field_types().items() if t == "double"]
STATE_ARRAYS = [f for f, t in ActuatorState.get_fields_and_field_types().items() if t == "sequence<double>"]


def decode_mcap(path):
    """(topic, log_time, message) of every message, with mcap-ros2-support."""
    out = []
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        for schema, channel, message, decoded in reader.iter_decoded_messages():
            assert schema.encoding == "ros2msg" and channel.message_encoding == "cdr"
            assert "offered_qos_profiles" in channel.metadata
            out.append((channel.topic, message.log_time, decoded))
        meta = {m.name: m.metadata for m in reader.iter_metadata()}
    return out, meta


def decode_rosbags(path):
    out = []
    with AnyReader([Path(path)]) as reader:
        # topic_type_hash: the REP-2016 hash of the embedded definition.
        with open(path, "rb") as f:
            for ch in make_reader(f).get_summary().channels.values():
                schema = next(c for c in reader.connections if c.topic == ch.topic).msgtype
                assert ch.metadata["topic_type_hash"] == reader.typestore.hash_rihs01(schema), (
                    f"crates/recording/src/msgs/type_hash.rs computes another hash: {schema} is "
                    f"{reader.typestore.hash_rihs01(schema)}"
                )
        for conn, t, raw in reader.messages():
            out.append((conn.topic, t, reader.deserialize(raw, conn.msgtype)))
    return out


def ns(stamp):
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def muscle_values(m):
    return [float(getattr(m, f)) for f in MUSCLE_FIELDS]


def same_state(a, b):
    """Every field of two ActuatorState-like objects (any of the three decoders), exactly."""
    assert a.tick == b.tick and a.model == b.model
    assert (a.header.stamp.sec, a.header.stamp.nanosec) == (b.header.stamp.sec, b.header.stamp.nanosec)
    assert list(a.joint) == list(b.joint)
    for f in STATE_ARRAYS:
        assert [float(x) for x in getattr(a, f)] == [float(x) for x in getattr(b, f)], f
    assert [m.name for m in a.muscles] == [m.name for m in b.muscles]
    for ma, mb in zip(a.muscles, b.muscles):
        assert muscle_values(ma) == muscle_values(mb)


@pytest.fixture(scope="module")
def workdir():
    return Path(tempfile.mkdtemp(prefix="muscle_actuator_rec_"))


def test_simulate_file_decodes_completely_and_matches_the_csv(workdir):
    out, csv_path = workdir / "pulse.mcap", workdir / "pulse.csv"
    subprocess.run(
        [NodeProcess.binary(), "simulate", "pulse", "--model", "hill", "--out", str(out),
         "--csv", str(csv_path)],
        check=True, capture_output=True,
    )
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    doctor(out)
    msgs, meta = decode_mcap(out)
    assert meta["muscle_actuator"]["model"] == "hill"
    assert "serialized_metadata" in meta["rosbag2"]
    states = [m for (t, _, m) in msgs if t == "/muscle_actuator/state"]
    assert len(states) == len(rows) == 3001
    for row, s in zip(rows, states):
        assert s.tick == round(float(row["time"]) * 1000)
        assert muscle_values(s.muscles[0]) == [float(row[f]) for f in MUSCLE_FIELDS]
    acts = [m for (t, _, m) in msgs if t == "/muscle_actuator/activation"]
    assert [list(a.excitation) for a in acts] == [[0.0], [1.0], [0.0]]
    assert [(a.header.stamp.sec, a.header.stamp.nanosec) for a in acts] == [(0, 0), (1, 0), (2, 0)]

    # rosbags, with only the embedded schemas: the same messages, the same values.
    rb = decode_rosbags(out)
    assert [(t, lt) for (t, lt, _) in rb] == [(t, lt) for (t, lt, _) in msgs]
    for (t, _, a), (_, _, b) in zip(msgs, rb):
        if t == "/muscle_actuator/state":
            same_state(a, b)
        else:
            assert list(a.excitation) == [float(x) for x in b.excitation]


@pytest.fixture(scope="module")
def recorded_node(peer, node_factory, workdir):
    """A node recording to workdir/runs, driven and watched by rclpy, then stopped."""
    rec_dir = workdir / "runs"
    node = node_factory("/t_rec", "-p", f"record_dir:={rec_dir}")
    states = peer.subscribe(ActuatorState, node.topic("~/state"))
    joints = peer.subscribe(JointState, "/t_rec/joint_states")
    peer.wait_matched_sub(states)
    peer.wait_matched_sub(joints)
    states.wait(timeout=10.0, what="a state")
    sent = []
    for u in (0.3, 0.8, 0.1):
        peer.activation(node.topic("~/activation"), flexor=u, extensor=0.2)
        sent.append(("activation", [u, 0.2]))
        time.sleep(0.2)
    peer.load(node.topic("~/external_load"), ["elbow"], [0.5])
    sent.append(("load", [0.5]))
    time.sleep(0.5)
    assert node.stop() == 0, node.output()
    files = sorted(rec_dir.glob("*.mcap"))
    assert len(files) == 1, files
    return files[0], states.msgs(), joints.msgs(), sent


def test_node_file_holds_what_rclpy_received(recorded_node):
    path, live_states, live_joints, sent = recorded_node
    doctor(path)
    msgs, meta = decode_mcap(path)
    assert meta["muscle_actuator"]["source"] == "node /t_rec/muscle_actuator"
    assert "rate_hz" in meta["muscle_actuator"]["parameters_json"]
    by_tick = {m.tick: m for (t, _, m) in msgs if t == "/t_rec/muscle_actuator/state"}
    assert live_states
    for s in live_states:
        same_state(s, by_tick[s.tick])
    js = {(m.header.stamp.sec, m.header.stamp.nanosec): m for (t, _, m) in msgs if t == "/t_rec/joint_states"}
    for j in live_joints:
        r = js[(j.header.stamp.sec, j.header.stamp.nanosec)]
        assert list(r.name) == list(j.name)
        for f in ("position", "velocity", "effort"):
            assert list(getattr(r, f)) == list(getattr(j, f))
    # Inputs as received, and as applied (stamped with the tick they took effect at).
    received = [list(m.excitation) for (t, _, m) in msgs if t == "/t_rec/muscle_actuator/activation"]
    assert received == [v for (k, v) in sent if k == "activation"]
    loads = [list(m.torque) for (t, _, m) in msgs if t == "/t_rec/muscle_actuator/external_load"]
    assert loads == [[0.5]]
    applied = [m for (t, _, m) in msgs if t == "/t_rec/muscle_actuator/applied/activation"]
    assert [list(a.excitation) for a in applied] == received
    # One clock: tick k is stamped tick_origin + k / rate, states and applied inputs alike.
    meta_rec = meta["muscle_actuator"]
    assert meta_rec["time_base"] == "wall"
    origin = int(meta_rec["tick_origin_ns"])
    rate = float(meta_rec["rate_hz"])
    for s in by_tick.values():
        assert ns(s.header.stamp) == origin + round(s.tick * 1e9 / rate)
    checked = 0
    for a in applied:
        tick = round((ns(a.header.stamp) - origin) * rate / 1e9)
        assert ns(a.header.stamp) == origin + round(tick * 1e9 / rate)
        after = by_tick.get(tick + 1)
        if after is not None:
            assert [m.excitation for m in after.muscles] == list(a.excitation)
            checked += 1
    assert checked >= 1

    # rosbags agrees on every message.
    rb = decode_rosbags(path)
    assert len(rb) == len(msgs)
    for (t, _, a), (_, _, b) in zip(msgs, rb):
        if t.endswith("/state"):
            same_state(a, b)


def test_node_file_has_one_clock_with_diagnostics_and_rosout(recorded_node):
    """Every log time and header stamp of a node recording is wall-clock time of the run; the
    node's /diagnostics and /rosout lines are in it."""
    path, _, _, _ = recorded_node
    msgs, meta = decode_mcap(path)
    start = int(meta["muscle_actuator"]["start_time_ns"])
    end = max(lt for (_, lt, _) in msgs)
    assert end - start < 60e9
    topics = {t for (t, _, _) in msgs}
    assert {"/diagnostics", "/rosout"} <= topics, topics
    for t, lt, m in msgs:
        assert start - 1e9 <= lt <= end, (t, lt, start)
        stamp = getattr(m, "header", None)
        stamp = stamp.stamp if stamp is not None else getattr(m, "stamp", None)
        if stamp is not None:
            assert start - 2e9 <= ns(stamp) <= end + 1e9, (t, ns(stamp), start, end)
    diag = [m for (t, _, m) in msgs if t == "/diagnostics"]
    assert len(diag) >= 1
    assert any(st.name.endswith("muscle_actuator: recorder") for d in diag for st in d.status)
    logs = [m for (t, _, m) in msgs if t == "/rosout"]
    assert all(l.name == "t_rec.muscle_actuator" for l in logs)
    assert any(" up: model " in l.msg for l in logs), [l.msg for l in logs]
    assert any(l.msg.startswith("stopped after ") for l in logs), [l.msg for l in logs]
    # rosbags reads them with the schemas embedded in the file only.
    rb = [(t, m) for (t, _, m) in decode_rosbags(path) if t in ("/diagnostics", "/rosout")]
    assert len(rb) == len(diag) + len(logs)


def test_node_file_replays_bit_for_bit(recorded_node, workdir):
    path = recorded_node[0]
    r = subprocess.run(
        [NodeProcess.binary(), "replay", str(path), "--out", str(workdir / "replayed.mcap")],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    assert "reproduced bit for bit" in r.stderr


def read_until_damage(path):
    """What a reader recovers from a cut file: every message of every complete chunk
    (mcap's StreamReader, stopping at the first incomplete record)."""
    channels, msgs = {}, []
    with open(path, "rb") as f:
        try:
            for rec in StreamReader(f, skip_magic=False, emit_chunks=False).records:
                if isinstance(rec, Channel):
                    channels[rec.id] = rec.topic
                elif isinstance(rec, Message):
                    msgs.append((channels[rec.channel_id], rec.log_time))
        except Exception:
            pass
    return msgs


def test_sigkill_loses_at_most_about_a_second(workdir):
    rec_dir = workdir / "killed"
    node = NodeProcess("/t_kill", ["-p", f"record_dir:={rec_dir}"]).start()
    try:
        wait_until(lambda: list(rec_dir.glob("*.mcap")), 10.0, what="the recording file")
        time.sleep(3.0)
        killed_at = time.time_ns()
        node.proc.send_signal(signal.SIGKILL)
        node.proc.wait()
    finally:
        node.stop()
    path = next(rec_dir.glob("*.mcap"))
    msgs = read_until_damage(path)
    states = [lt for (t, lt) in msgs if t.endswith("/state")]
    assert len(states) > 1000
    assert killed_at - max(states) < 1.5e9, (killed_at - max(states)) / 1e9
    # `recover` rewrites it as a complete file: a summary, and every message read above (the
    # stream reader may also yield the first messages of the chunk cut short, never recovered).
    out = workdir / "recovered.mcap"
    r = subprocess.run(
        [NodeProcess.binary(), "recover", str(path), str(out)], capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    assert "recovered " in r.stderr, r.stderr
    with open(out, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        assert summary is not None
        recovered = [(ch.topic, m.log_time) for _, ch, m in reader.iter_messages(log_time_order=False)]
    assert summary.statistics.message_count == len(recovered)
    assert len(recovered) > 1000
    assert recovered == msgs[: len(recovered)]
    assert max(lt for (t, lt) in recovered if t.endswith("/state")) > max(states) - 1.5e9


def recorder_error(diags, fqn):
    """The node's recorder status on /diagnostics if it is at level ERROR, else None."""
    for d in diags.msgs():
        for st in d.status:
            if st.name == f"{fqn}: recorder" and st.level in (2, b"\x02"):
                return st
    return None


def test_unwritable_record_dir_keeps_the_node_running(peer, workdir):
    blocker = workdir / "a_file"
    blocker.write_text("not a directory")
    node = NodeProcess("/t_norec", ["-p", f"record_dir:={blocker}/runs"]).start()
    try:
        diags = peer.subscribe(DiagnosticArray, "/diagnostics")
        states = peer.subscribe(ActuatorState, "/t_norec/muscle_actuator/state")

        st = wait_until(lambda: recorder_error(diags, "/t_norec/muscle_actuator"), 15.0, what="the recorder's error on /diagnostics")
        assert "a_file" in st.message
        states.wait(timeout=10.0, what="a state")
        assert node.alive()
    finally:
        assert node.stop() == 0
    assert "not recording" in node.output()


class NodeOnSmallDisk(NodeProcess):
    """The node in a private mount namespace whose record_dir is a tmpfs of `size`."""

    def __init__(self, namespace, mount_point, size, ros_args=()):
        super().__init__(namespace, ["-p", f"record_dir:={mount_point}", *ros_args])
        self.mount_point = str(mount_point)
        self.size = size

    def command(self):
        script = 'mount -t tmpfs -o size="$1" tmpfs "$2" && shift 2 && exec "$@"'
        return ["unshare", "-m", "--propagation", "private", "sh", "-c", script, "sh",
                self.size, self.mount_point, *super().command()]


def test_full_disk_stops_the_recording_not_the_node(peer, workdir):
    if os.geteuid() != 0 or subprocess.run(["unshare", "-m", "true"]).returncode != 0:
        pytest.skip("needs root to mount a private tmpfs")
    mount_point = workdir / "small_disk"
    mount_point.mkdir()
    # About 90 kB per simulated second at 1 kHz: 256 kB fills within a few seconds.
    node = NodeOnSmallDisk("/t_full", mount_point, "256k").start()
    try:
        diags = peer.subscribe(DiagnosticArray, "/diagnostics")
        states = peer.subscribe(ActuatorState, "/t_full/muscle_actuator/state")

        st = wait_until(lambda: recorder_error(diags, "/t_full/muscle_actuator"), 30.0, what="the recorder's error on /diagnostics")
        # The simulation goes on: states keep coming, ticks keep advancing.
        first = states.wait(timeout=10.0, what="a state after the disk filled")
        time.sleep(1.0)
        later = states.msgs()[-1]
        assert later.tick > first.tick + 500, (first.tick, later.tick)
        assert node.alive()
        assert "No space left on device" in st.message, st.message
    finally:
        assert node.stop() == 0
