"""The live view's protocol: the node's Foxglove WebSocket server (`foxglove_port`), seen by the
Foxglove app's own client and CDR decoder (tests/foxglove/client.mjs, Node.js), by a raw
WebSocket client and by rclpy. The channels carry the recording's schemas and bytes, and `~/state`
decodes as rclpy receives it; client publish, parameters and services behave as their DDS
counterparts; the simulated clock is sent as time; both subprotocol names are taken and no other.
Hostile and slow clients, many clients and the port are test_foxglove_hostile.py's."""

import re
import struct
import time

import pytest
from rclpy.parameter import Parameter

from foxglove_peers import (
    BINARY, SUBPROTOCOLS, FoxgloveClient, RawWebSocket, RecordingTail, assert_same, code_lines,
    force_rises, log_lines, needs_node, rclpy_names, rclpy_values, recorded_schemas, recording_of,
    rejections, relaxed, require_client, same_bits, sections, start_live_node,
)
from helpers import ROOT, Watch, muscle, wait_until
from test_clock import step as dds_step

pytestmark = needs_node


@pytest.fixture(scope="module", autouse=True)
def client_installed():
    require_client()


@pytest.fixture
def fox():
    """Starts Node.js clients for a test and closes them at its end (the node serves at most 16
    at once)."""
    started = []

    def start(port, subprotocol="foxglove.sdk.v1"):
        c = FoxgloveClient(port, subprotocol)
        started.append(c)
        return c

    yield start
    for c in started:
        c.close()


# --- the node under test ------------------------------------------------------------------------

NS = "/t_fox"


@pytest.fixture(scope="module")
def rec_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("fox") / "runs"


@pytest.fixture(scope="module")
def node(node_factory, rec_dir):
    """The node most tests use: recording, its states at 100 Hz (ticks at 1 kHz)."""
    return start_live_node(
        node_factory, NS, "-p", f"record_dir:={rec_dir}", "-p", "publish_rate_hz:=100.0"
    )


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node)


@pytest.fixture(scope="module")
def recording(node, rec_dir):
    return recording_of(rec_dir)


def published_topics(node):
    return {
        node.topic("~/state"): "muscle_actuator_msgs/msg/ActuatorState",
        node.topic("joint_states"): "sensor_msgs/msg/JointState",
        "/diagnostics": "diagnostic_msgs/msg/DiagnosticArray",
        "/rosout": "rcl_interfaces/msg/Log",
    }


def check_channels(channels, expected):
    """The channels are `expected` ({topic: type}), cdr with ros2msg schemas, distinct ids."""
    assert {t: c["schemaName"] for t, c in channels.items()} == expected
    assert len({c["id"] for c in channels.values()}) == len(channels)
    for c in channels.values():
        assert c["encoding"] == "cdr" and c["schemaEncoding"] == "ros2msg", c


# --- channels and schemas -----------------------------------------------------------------------


@pytest.mark.parametrize("subprotocol", SUBPROTOCOLS)
def test_channels_carry_the_recordings_schemas(node, fox, recording, subprotocol):
    c = fox(node.port, subprotocol)
    assert c.wait("open")["protocol"] == subprotocol
    info, channels = c.connected()
    assert info["name"] == node.fqn
    assert sorted(info["capabilities"]) == ["clientPublish", "parameters", "services"]
    assert sorted(info["supportedEncodings"]) == ["cdr", "json"]
    expected = published_topics(node)
    check_channels(channels, expected)
    recorded = recorded_schemas(recording, expected)
    for topic, ch in channels.items():
        assert (ch["schemaName"], ch["schema"]) == recorded[topic], topic
    # The wall clock is not sent as time.
    time.sleep(1.0)
    assert c.events("time") == []


@pytest.fixture(scope="module")
def lock_node(node_factory, tmp_path_factory):
    """lockstep, with the elbow driven (so ~/joint_efforts exists), recording."""
    d = tmp_path_factory.mktemp("fox_lock")
    cfg = d / "driven_elbow.toml"
    text = (ROOT / "crates" / "core" / "configs" / "elbow.toml").read_text()
    cfg.write_text(text.replace("initial_angle = 0.0", "initial_angle = 0.0\ndriven = true", 1))
    node = start_live_node(
        node_factory, "/t_fox_lock", "-p", "clock:=lockstep", "-p", "model:=hill",
        "-p", f"config:={cfg}", "-p", f"record_dir:={d / 'runs'}",
    )
    node.rec_dir = d / "runs"
    return node


@pytest.mark.parametrize("subprotocol", SUBPROTOCOLS)
def test_simulated_time_adds_clock_and_time_driven_joints_add_efforts(lock_node, fox, subprotocol):
    c = fox(lock_node.port, subprotocol)
    assert c.wait("open")["protocol"] == subprotocol
    info, channels = c.connected()
    assert info["name"] == lock_node.fqn
    assert sorted(info["capabilities"]) == ["clientPublish", "parameters", "services", "time"]
    expected = published_topics(lock_node)
    expected["/clock"] = "rosgraph_msgs/msg/Clock"
    expected[lock_node.topic("~/joint_efforts")] = "std_msgs/msg/Float64MultiArray"
    check_channels(channels, expected)
    recorded = recorded_schemas(recording_of(lock_node.rec_dir), set(expected) - {"/clock"})
    for topic, ch in channels.items():
        if topic != "/clock":
            assert (ch["schemaName"], ch["schema"]) == recorded[topic], topic
    # /clock is not recorded: its definition, and the one it embeds as every recorded schema has it.
    clock = sections(channels["/clock"]["schema"])
    assert code_lines(clock[""]) == ["builtin_interfaces/Time clock"]
    state = sections(recorded[lock_node.topic("~/state")][1])
    assert clock["builtin_interfaces/Time"] == state["builtin_interfaces/Time"]


@pytest.mark.parametrize("subprotocol", ["foxglove.websocket.v2", "foxglove", "", None])
def test_other_subprotocols_are_refused_with_400(node, fox, subprotocol):
    ws = RawWebSocket(node.port)
    try:
        status, _ = ws.handshake(subprotocol)
    finally:
        ws.close(graceful=False)
    assert status == 400, status
    if subprotocol:  # the Foxglove client sees the same refusal
        c = fox(node.port, subprotocol)
        e = c.wait("error", timeout=10.0)
        assert e.get("status") == 400, e


# --- ~/state as Foxglove decodes it -------------------------------------------------------------


def test_state_decodes_as_rclpy_receives_it_and_as_recorded(node, watch, fox, recording):
    c = fox(node.port)
    c.connected()
    topic = node.topic("~/state")
    t0 = time.monotonic()
    since = c.mark()
    c.subscribe(topic, max=300, raw=True)
    got = c.wait_count("message", 300, topic, timeout=30.0, since=since)
    time.sleep(0.5)  # rclpy's copies of the same ticks
    by_tick = {m.tick: m for m in watch.state.msgs(since=t0 - 1.0)}
    common = [e for e in got if e["data"]["tick"] in by_tick]
    assert len(common) >= 50, f"only {len(common)} of 300 ticks also reached rclpy"
    for e in common:
        assert_same(by_tick[e["data"]["tick"]], e["data"], f"tick {e['data']['tick']}")
    # Each is stamped, for Foxglove's plots, with its own header stamp (the node's clock).
    for e in got:
        stamp = e["data"]["header"]["stamp"]
        assert e["receiveTimeNs"] == stamp["sec"] * 10**9 + stamp["nanosec"], e["receiveTimeNs"]
    # The payloads are the recording's bytes, encapsulation header included.
    assert all(bytes.fromhex(e["hex"])[:4] == b"\x00\x01\x00\x00" for e in got)
    wanted = {bytes.fromhex(e["hex"]) for e in got[:100]}
    tail = RecordingTail(recording, keep=[topic])
    tail.wait(lambda t: wanted <= set(t.payloads[topic]), "the same payloads in the recording")


# --- client publish -----------------------------------------------------------------------------


def header():
    return {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": ""}


def publisher(fox, node):
    c = fox(node.port)
    c.connected()
    return c


def test_an_activation_command_in_cdr_raises_the_flexors_force(node, watch, fox, recording):
    c = publisher(fox, node)
    topic = node.topic("~/activation")
    c.advertise(topic, "cdr", "muscle_actuator_msgs/msg/ActivationCommand")
    relaxed(watch)
    u = 0.987654
    c.publish(topic, {"header": header(), "muscle": ["flexor"], "excitation": [u]})
    force_rises(watch, u, "the flexor's force up after the Foxglove command")
    # Recorded as received and as applied, as the DDS commands are.
    applied = node.topic("~/applied/activation")
    tail = RecordingTail(recording, keep=[topic, applied])
    tail.wait(lambda t: any(list(m.excitation) == [u] for m in t.decoded(topic)),
              f"the command on {topic} in the recording")
    tail.wait(lambda t: any(u in list(m.excitation) for m in t.decoded(applied)),
              f"the command on {applied} in the recording")


def test_an_activation_array_in_json_raises_the_flexors_force(node, watch, fox, recording):
    c = publisher(fox, node)
    topic = node.topic("~/activation_array")
    c.advertise(topic, "json", "std_msgs/msg/Float64MultiArray")
    relaxed(watch)
    values = [0.876543, 0.012345]
    c.publish(topic, {"layout": {"dim": [], "data_offset": 0}, "data": values})
    force_rises(watch, values[0], "the flexor's force up after the Foxglove array")
    assert muscle(watch.state.last(), "extensor").excitation == values[1]
    applied = node.topic("~/applied/activation")
    tail = RecordingTail(recording, keep=[topic, applied])
    tail.wait(lambda t: any(list(m.data) == values for m in t.decoded(topic)),
              f"the array on {topic} in the recording")
    tail.wait(lambda t: any(set(values) <= set(m.excitation) for m in t.decoded(applied)),
              f"the array's excitations on {applied} in the recording")


def test_a_muscle_topic_and_the_load_take_foxglove_commands(node, watch, fox):
    c = publisher(fox, node)
    flexor = node.topic("~/flexor/cmd_activation")
    load = node.topic("~/external_load")
    c.advertise(flexor, "cdr", "std_msgs/msg/Float64")
    c.advertise(load, "json", "muscle_actuator_msgs/msg/ExternalLoad")
    c.publish(flexor, {"data": 0.654321})
    watch.state.wait(lambda s: muscle(s, "flexor").excitation == 0.654321, timeout=10.0,
                     what="the flexor's topic command in force")
    c.publish(load, {"joint": ["elbow"], "torque": [0.4321]})  # JSON: missing fields default
    watch.state.wait(lambda s: list(s.external_torque) == [0.4321], timeout=10.0,
                     what="the load in force")
    watch.load(0.0)


@pytest.mark.parametrize("kind", ["activation", "activation_array"])
def test_a_malformed_command_is_refused_as_over_dds(peer, node, watch, fox, recording, kind):
    """Wrong number of values: refused whole with the DDS topic's reason and log line, counted,
    and the force in force stays."""
    c = publisher(fox, node)
    topic = node.topic(f"~/{kind}")
    if kind == "activation":
        c.advertise(topic, "cdr", "muscle_actuator_msgs/msg/ActivationCommand")
        bad = {"header": header(), "muscle": ["flexor", "extensor"], "excitation": [0.3456]}
        bad_values = bad["excitation"]

        def over_dds():
            peer.raw_activation(topic, ["flexor", "extensor"], [0.3456])
    else:
        from std_msgs.msg import Float64MultiArray

        c.advertise(topic, "json", "std_msgs/msg/Float64MultiArray")
        bad = {"layout": {"dim": [], "data_offset": 0}, "data": [0.3456]}
        bad_values = bad["data"]

        def over_dds():
            peer.publisher(Float64MultiArray, topic).publish(Float64MultiArray(data=[0.3456]))

    watch.activation(flexor=1.0, extensor=0.0)
    force_rises(watch, 1.0, "the flexor's force up")
    time.sleep(1.1)  # at its plateau; and the node logs one line of a kind a second
    held = muscle(watch.state.last(), "flexor").force
    before, _ = rejections(watch, "length_mismatch")
    t0 = time.monotonic()
    c.publish(topic, bad)
    wait_until(lambda: rejections(watch, "length_mismatch")[0] > before, 10.0,
               what="the Foxglove command counted as rejected")
    _, reason = rejections(watch, "length_mismatch")
    later = [s for (t, s) in watch.state.timed(t0)]
    assert later and all(muscle(s, "flexor").excitation == 1.0 for s in later)
    now = muscle(later[-1], "flexor").force
    assert abs(now - held) < 0.02 * held, (held, now)
    # The same command over DDS: the same reason, the same log line.
    time.sleep(1.1)
    over_dds()
    wait_until(lambda: rejections(watch, "length_mismatch")[0] > before + 1, 10.0,
               what="the DDS command counted as rejected")
    assert rejections(watch, "length_mismatch")[1] == reason
    lines = [l for l in log_lines(node) if l.startswith("[WARN]") and "]: " + reason in l]
    assert len(lines) == 2, (reason, lines)
    # Both recorded as received, neither applied.
    applied = node.topic("~/applied/activation")
    tail = RecordingTail(recording, keep=[topic, applied])
    tail.wait(lambda t: len([m for m in t.decoded(topic) if values_of(m) == bad_values]) == 2,
              f"both refused commands on {topic} in the recording")
    assert not any(0.3456 in list(m.excitation) for m in tail.decoded(applied))


def values_of(msg):
    """An activation command's excitations or an array's data."""
    return list(msg.excitation if hasattr(msg, "excitation") else msg.data)


@pytest.mark.parametrize("rel, schema", [
    ("~/bogus", "std_msgs/msg/Float64"),
    ("~/state", "muscle_actuator_msgs/msg/ActuatorState"),
    ("~/activation", "std_msgs/msg/String"),
    ("~/activation_array", "std_msgs/msg/Float64"),
])
def test_advertising_what_the_node_does_not_take_is_an_error_status(node, fox, rel, schema):
    c = publisher(fox, node)
    topic = node.topic(rel)
    since = c.mark()
    c.advertise(topic, "cdr", schema)
    status = c.wait("status", lambda e: e["level"] == 2, 10.0, since, what="an error status")
    assert topic in status["message"], status
    # Nothing else: the connection stays and answers.
    assert c.parameters(["model"], "after")["model"]["value"] in ("hill", "huxley", "huxley-pde")
    assert c.events("close", since) == [] and len(c.events("status", since)) == 1


def test_mistakes_within_the_protocol_are_a_status_and_the_connection_stays(node):
    """An unknown channel id, either way: a warning or error status (level 1 or 2)."""
    ws = RawWebSocket(node.port)
    try:
        ws.open()
        ws.recv_json("serverInfo")
        ws.send_json({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 999999}]})
        assert ws.recv_json("status")["level"] in (1, 2)
        # Data on a client channel never advertised.
        ws.send(BINARY, b"\x01" + struct.pack("<I", 424242) + b"\x00\x01\x00\x00")
        assert ws.recv_json("status")["level"] in (1, 2)
        ws.send_json({"op": "getParameters", "parameterNames": ["model"], "id": "still here"})
        assert ws.recv_json("parameterValues")["id"] == "still here"
    finally:
        ws.close()


# --- parameters ---------------------------------------------------------------------------------


def test_get_parameters_gives_every_parameter_as_rclpy_sees_it(peer, node, fox):
    c = publisher(fox, node)
    got = c.parameters([], "all")
    names = rclpy_names(peer, node)
    assert sorted(got) == sorted(names)
    assert {"model", "rate_hz", "foxglove_port", "record", "clock"} <= set(got)
    want = rclpy_values(peer, node, names)
    for name, p in got.items():
        v = want[name]
        if isinstance(v, float):
            assert p.get("type") == "float64" and same_bits(p["value"], v), p
        else:
            assert p["value"] == v and type(p["value"]) is type(v) and p.get("type") is None, p
    assert got["foxglove_port"]["value"] == node.port
    # Named ones, answered with the request's id.
    some = c.parameters(["model", "rate_hz"], "some")
    assert sorted(some) == ["model", "rate_hz"]


def rate_param(value):
    return {"name": "publish_rate_hz", "value": value, "type": "float64"}


def test_an_accepted_change_is_answered_and_seen_by_rclpy(peer, node, fox):
    c = publisher(fox, node)
    (before,) = rclpy_values(peer, node, ["publish_rate_hz"]).values()
    try:
        since = c.mark()
        c.send("setParameters", parameters=[rate_param(500)], id="set1")
        answer = c.wait("parameterValues", lambda e: e.get("id") == "set1", 15.0, since)
        (p,) = [p for p in answer["parameters"] if p["name"] == "publish_rate_hz"]
        assert p["value"] == 500 and p.get("type") == "float64", p
        assert rclpy_values(peer, node, ["publish_rate_hz"]) == {"publish_rate_hz": 500.0}
        assert c.parameters(["publish_rate_hz"], "get1")["publish_rate_hz"]["value"] == 500
    finally:
        c.send("setParameters", parameters=[rate_param(before)], id="undo")
        c.wait("parameterValues", lambda e: e.get("id") == "undo", 15.0)
    assert rclpy_values(peer, node, ["publish_rate_hz"]) == {"publish_rate_hz": before}


@pytest.mark.parametrize("name, value, type_", [
    ("rate_hz", -1.0, "float64"),
    ("model", "bogus", None),
    ("clock", "sim", None),
    ("config", "/nonexistent/limb.toml", None),
])
def test_a_refused_change_says_what_rclpy_is_told(peer, node, fox, name, value, type_):
    (before,) = rclpy_values(peer, node, [name]).values()
    client = peer.param_client(node)
    resp = peer.await_future(client.set_parameters([Parameter(name, value=value)]))
    (result,) = resp.results
    assert not result.successful and result.reason
    c = publisher(fox, node)
    since = c.mark()
    param = {"name": name, "value": value, **({"type": type_} if type_ else {})}
    c.send("setParameters", parameters=[param], id="refused")
    status = c.wait("status", lambda e: e["level"] == 2, 15.0, since, what="the refusal")
    assert result.reason in status["message"], (result.reason, status)
    # The value stays, for rclpy and the live view (an answer to the id, if any, says so too).
    assert rclpy_values(peer, node, [name]) == {name: before}
    assert c.parameters([name], "after")[name]["value"] == before
    for answer in c.events("parameterValues", since):
        for p in answer["parameters"]:
            if p["name"] == name:
                assert p["value"] == before, answer


# --- services -----------------------------------------------------------------------------------


def test_reset_and_step_are_advertised_with_their_schemas(node, fox, recording):
    c = publisher(fox, node)
    services = c.services()
    reset, step = node.topic("~/reset"), node.topic("~/step")
    assert sorted(services) == sorted([reset, step])
    assert services[reset]["type"] == "std_srvs/srv/Trigger"
    assert services[step]["type"] == "muscle_actuator_msgs/srv/Step"
    for s in services.values():
        for part in ("request", "response"):
            assert s[part]["encoding"] == "cdr" and s[part]["schemaEncoding"] == "ros2msg", s
    assert code_lines(services[reset]["request"]["schema"]) == []
    assert code_lines(services[reset]["response"]["schema"]) == ["bool success", "string message"]
    assert code_lines(services[step]["request"]["schema"]) == ["int64 ticks"]
    response = sections(services[step]["response"]["schema"])
    unqualified = [re.sub(r"^\S+/", "", line) for line in code_lines(response[""])]
    assert unqualified == ["bool success", "string message", "uint64 tick", "ActuatorState state"]
    # The state it answers with is defined as the recorded one.
    state = sections(recorded_schemas(recording, [node.topic("~/state")])[node.topic("~/state")][1])
    assert response["muscle_actuator_msgs/ActuatorState"] == state[""]
    for name, text in state.items():
        if name:
            assert response[name] == text, name


RESET_ANSWER = re.compile(r"reset to the initial state after \d+ ticks")


def test_reset_answers_as_the_dds_service(peer, node, watch, fox):
    c = publisher(fox, node)
    c.services()
    watch.state.wait(lambda s: s.tick > 500, timeout=10.0, what="500 ticks run")
    t0 = time.monotonic()
    answer = c.call(node.topic("~/reset"), {})
    assert answer["event"] == "serviceResponse", answer
    assert answer["data"]["success"] is True, answer
    assert RESET_ANSWER.fullmatch(answer["data"]["message"]), answer
    watch.state.wait(lambda s: s.tick < 300, timeout=10.0, since=t0,
                     what="the ticks counted again from 0")
    dds = peer.reset(node)
    assert dds.success and RESET_ANSWER.fullmatch(dds.message), dds.message


def test_step_without_lockstep_is_refused_as_over_dds(peer, node, fox):
    c = publisher(fox, node)
    c.services()
    answer = c.call(node.topic("~/step"), {"ticks": 5})
    assert answer["event"] == "serviceResponse", answer
    dds = dds_step(peer, node, 5)
    assert answer["data"]["success"] is False and not dds.success
    assert answer["data"]["message"] == dds.message
    assert answer["data"]["message"].startswith("~/step needs clock:=lockstep; ")


def test_step_in_lockstep_advances_the_ticks_asked(lock_node, fox):
    c = fox(lock_node.port)
    c.connected()
    c.services()
    topic = lock_node.topic("~/state")
    c.subscribe(topic, max=1000)
    step = lock_node.topic("~/step")
    first = c.call(step, {"ticks": 1})["data"]
    assert first["success"] is True, first
    since = c.mark()
    second = c.call(step, {"ticks": 7})["data"]
    assert second["success"] is True and second["tick"] == first["tick"] + 7, (first, second)
    assert second["state"]["tick"] == second["tick"]
    c.wait("message", lambda e: e["topic"] == topic and e["data"]["tick"] == second["tick"],
           10.0, since, what=f"~/state at tick {second['tick']}")
    refused = c.call(step, {"ticks": 0})["data"]
    assert refused["success"] is False and "ticks" in refused["message"], refused


# --- time ---------------------------------------------------------------------------------------


def test_a_simulated_clock_is_sent_as_time(short_lived, fox):
    sim = start_live_node(
        short_lived, "/t_fox_sim", "-p", "clock:=sim", "-p", "real_time_factor:=2.0",
        "-p", "model:=hill", "-p", "publish_rate_hz:=100.0", "-p", "record:=false",
    )
    c = fox(sim.port)
    info, channels = c.connected()
    assert "time" in info["capabilities"] and "/clock" in channels
    c.subscribe(sim.topic("~/state"), max=50)
    first = c.wait("time", timeout=10.0)
    t0 = time.monotonic()
    time.sleep(2.0)
    wall = time.monotonic() - t0
    times = [e["ns"] for e in c.events("time")]
    assert len(times) >= 10, times
    assert times == sorted(times), "time went back"
    assert all(t % 1_000_000 == 0 for t in times), "not on a tick of 1 ms"
    rate = (times[-1] - first["ns"]) / 1e9 / wall
    assert 1.5 < rate < 2.5, f"{rate:.2f} simulated seconds per wall second with real_time_factor 2"
    # The states' stamps are on the same clock: near the time sent just before each.
    last_time, checked = None, 0
    for e in c.history():
        if e["event"] == "time":
            last_time = e["ns"]
        elif e["event"] == "message" and last_time is not None:
            stamp = e["data"]["header"]["stamp"]
            stamp_ns = stamp["sec"] * 10**9 + stamp["nanosec"]
            assert abs(stamp_ns - last_time) < 5 * 10**8, (stamp_ns, last_time)
            checked += 1
    assert checked >= 10, checked
