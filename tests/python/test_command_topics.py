"""The simple command topics, as ros2_control's forward_command_controller and the HBP muscle
interface offer them: `~/<muscle>/cmd_activation` (std_msgs/Float64) per muscle and
`~/activation_array` (std_msgs/Float64MultiArray, in the configuration's muscle order). Same
validation and tick-boundary rule as `~/activation`; recorded, and the run replays bit for bit."""

import math
import subprocess
import time

import pytest
from mcap.reader import make_reader
from std_msgs.msg import Float64, Float64MultiArray

from helpers import NodeProcess, Watch, wait_until

NS = "/t_cmd"


@pytest.fixture(scope="module")
def rec_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("cmd") / "runs"


@pytest.fixture(scope="module")
def node(node_factory, rec_dir):
    return node_factory(NS, "-p", f"record_dir:={rec_dir}")


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node)


def excitations(state):
    return {m.name: m.excitation for m in state.muscles}


def send_until(watch, send, want, what):
    return watch._until_seen(
        send, lambda s: all(abs(excitations(s)[k] - v) < 1e-12 for k, v in want.items()), 10.0, what
    )


def test_one_muscle_topic_each(peer, node, watch):
    flexor = peer.publisher(Float64, node.topic("~/flexor/cmd_activation"))
    extensor = peer.publisher(Float64, node.topic("~/extensor/cmd_activation"))
    send_until(watch, lambda: flexor.publish(Float64(data=0.7)), {"flexor": 0.7}, "flexor 0.7")
    s = send_until(watch, lambda: extensor.publish(Float64(data=0.3)),
                   {"flexor": 0.7, "extensor": 0.3}, "extensor 0.3, flexor still 0.7")
    assert excitations(s) == {"flexor": 0.7, "extensor": 0.3}
    # Out of [0, 1]: clamped, as on ~/activation.
    send_until(watch, lambda: flexor.publish(Float64(data=1.5)), {"flexor": 1.0}, "flexor clamped")


def test_the_array_in_configuration_order(peer, node, watch):
    pub = peer.publisher(Float64MultiArray, node.topic("~/activation_array"))
    send_until(watch, lambda: pub.publish(Float64MultiArray(data=[0.2, 0.9])),
               {"flexor": 0.2, "extensor": 0.9}, "array [0.2, 0.9]")


@pytest.mark.parametrize("data, kind", [([0.5], "rejected_length_mismatch"),
                                        ([0.5, 0.5, 0.5], "rejected_length_mismatch"),
                                        ([math.nan, 0.5], "rejected_non_finite")])
def test_bad_arrays_are_rejected_whole(peer, node, watch, data, kind):
    pub = peer.publisher(Float64MultiArray, node.topic("~/activation_array"))
    before = int(watch.diagnostics()["inputs"][kind])
    t0 = time.monotonic()
    pub.publish(Float64MultiArray(data=data))
    wait_until(lambda: int(watch.diagnostics()["inputs"][kind]) > before, 10.0, what=kind)
    # Nothing changed: the last valid command stays in force.
    later = [s for t, s in watch.state.timed(t0)]
    assert later and all(excitations(s) == excitations(later[0]) for s in later)


def test_a_nan_on_a_muscle_topic_is_rejected(peer, node, watch):
    pub = peer.publisher(Float64, node.topic("~/flexor/cmd_activation"))
    before = int(watch.diagnostics()["inputs"]["rejected_non_finite"])
    pub.publish(Float64(data=math.nan))
    wait_until(lambda: int(watch.diagnostics()["inputs"]["rejected_non_finite"]) > before, 10.0,
               what="the NaN rejected")


def test_recorded_and_replayed_bit_for_bit(peer, node, watch, rec_dir, tmp_path):
    flexor = peer.publisher(Float64, node.topic("~/flexor/cmd_activation"))
    arr = peer.publisher(Float64MultiArray, node.topic("~/activation_array"))
    send_until(watch, lambda: arr.publish(Float64MultiArray(data=[0.4, 0.1])),
               {"flexor": 0.4, "extensor": 0.1}, "array")
    send_until(watch, lambda: flexor.publish(Float64(data=0.05)), {"flexor": 0.05}, "flexor")
    time.sleep(0.3)
    assert node.stop() == 0, node.output()
    path = sorted(rec_dir.glob("*.mcap"))[0]
    with open(path, "rb") as f:
        topics = {c.topic: c for c in make_reader(f).get_summary().channels.values()}
    for t in (node.topic("~/activation_array"), node.topic("~/flexor/cmd_activation"),
              node.topic("~/extensor/cmd_activation")):
        assert t in topics, sorted(topics)
    out = tmp_path / "again.mcap"
    r = subprocess.run([NodeProcess.binary(), "replay", str(path), "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "reproduced bit for bit" in r.stderr, r.stdout + r.stderr


def test_muscles_whose_names_make_no_topic(peer, tmp_path):
    """Muscle names that are not ROS name tokens get no `cmd_activation` topic (said at start-up);
    the node runs on and the other activation topics serve them."""
    cfg = tmp_path / "dashed.toml"
    cfg.write_text('[[muscle]]\nname = "flex-or"\n[[muscle]]\nname = "ext-ensor"\n')
    node = NodeProcess("/t_cmd_dashed", ["-p", f"config:={cfg}", "-p", "record:=false"])
    node.start()
    try:
        w = Watch(peer, node, diagnostics=False)
        arr = peer.publisher(Float64MultiArray, node.topic("~/activation_array"))
        send_until(w, lambda: arr.publish(Float64MultiArray(data=[0.6, 0.2])),
                   {"flex-or": 0.6, "ext-ensor": 0.2}, "array on dashed names")
        time.sleep(1.0)
        assert node.alive(), node.output()
        assert node.output().count("no ~/<muscle>/cmd_activation topic for muscle") == 2, node.output()
    finally:
        assert node.stop() == 0, node.output()
