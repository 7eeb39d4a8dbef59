"""Following an external clock (docs/time.md): with `use_sim_time:=true` and `clock` wall, an
rclpy /clock publisher drives the node. Each clock message advances it by the whole ticks it
covers, stamped with that clock; a paused clock pauses ~/state; a clock that jumps back resets
the actuator with a report, and the node goes on from the new time. The recording's ticks are
anchored at the first /clock time, and replay gives them back bit for bit."""

import subprocess
import time

from builtin_interfaces.msg import Time
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from muscle_actuator_msgs.msg import ActuatorState
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from rosgraph_msgs.msg import Clock

from helpers import NodeProcess, reliable, wait_until

T0 = 5000 * 10**9  # the external clock's time when the node first hears it, ns
MS = 10**6

# As a simulator publishes /clock (and rclpy's time source subscribes): best effort.
CLOCK_QOS = QoSProfile(
    reliability=ReliabilityPolicy.BEST_EFFORT,
    history=HistoryPolicy.KEEP_LAST,
    depth=10,
    durability=DurabilityPolicy.VOLATILE,
)


def ns(stamp):
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def clock_msg(t_ns):
    return Clock(clock=Time(sec=t_ns // 10**9, nanosec=t_ns % 10**9))


class Follower:
    """A node following /clock, a /clock publisher and a ~/state subscriber."""

    def __init__(self, peer, node):
        self.peer = peer
        self.node = node
        self.states = peer.subscribe(ActuatorState, node.topic("~/state"), reliable(1000))
        peer.wait_matched_sub(self.states)
        self.clock = peer.publisher(Clock, "/clock", CLOCK_QOS)
        self.now = None

    def tick_to(self, t_ns, tick, timeout=10.0):
        """Publishes /clock at t_ns (again while the node has not reached `tick`: a best-effort
        message can be lost) and returns the state of `tick`."""
        self.now = t_ns
        start = time.monotonic()
        while time.monotonic() < start + timeout:
            self.clock.publish(clock_msg(t_ns))
            for s in self.states.msgs(since=start):
                if s.tick == tick:
                    return s
            time.sleep(0.02)
        last = self.states.last()
        raise AssertionError(f"no state of tick {tick} (last: {last.tick if last else None})")

    def warm_up(self):
        """Anchors the clock at T0, then advances tick by tick with a command until a state
        shows it (the first commands of a new writer can arrive late)."""
        # Until the node has heard T0 (its reader may match our writer late).
        def anchored():
            self.clock.publish(clock_msg(T0))
            return "following /clock: tick 0 at 5000.000000 s" in self.node.output()

        wait_until(anchored, 10.0, interval=0.02, what="the node anchored at T0")
        topic = self.node.topic("~/activation")
        for k in range(1, 200):
            self.peer.activation(topic, flexor=0.5, extensor=0.5)
            time.sleep(0.02)
            s = self.tick_to(T0 + k * MS, k)
            if all(m.excitation == 0.5 for m in s.muscles):
                return k
        raise AssertionError("the node never showed the warm-up command")


def test_clock_publisher_drives_the_node_and_the_run_replays(peer, node_factory, tmp_path):
    rec_dir = tmp_path / "runs"
    n = node_factory(
        "/t_follow", "-p", "use_sim_time:=true", "-p", "model:=huxley",
        "-p", f"record_dir:={rec_dir}",
    )
    f = Follower(peer, n)
    k = f.warm_up()
    # Every state so far is stamped with the followed clock: tick k at T0 + k ms.
    assert all(ns(s.header.stamp) == T0 + s.tick * MS for s in f.states.msgs())
    # A clock message advances by the whole ticks it covers: 20.5 ms more is 20 ticks.
    s = f.tick_to(T0 + (k + 20) * MS + MS // 2, k + 20)
    time.sleep(0.3)
    assert max(x.tick for x in f.states.msgs()) == k + 20
    assert ns(s.header.stamp) == T0 + (k + 20) * MS

    # A paused clock pauses the node: no state for 0.5 s.
    before = len(f.states.msgs())
    time.sleep(0.5)
    assert len(f.states.msgs()) == before

    # An input received before a clock message takes effect at the first tick it covers.
    peer.activation(n.topic("~/activation"), flexor=0.9, extensor=0.1)
    time.sleep(0.3)
    assert len(f.states.msgs()) == before  # still paused
    first = f.tick_to(T0 + (k + 21) * MS, k + 21)
    assert [m.excitation for m in first.muscles] == [0.9, 0.1]
    f.tick_to(T0 + (k + 120) * MS, k + 120)
    assert n.stop() == 0, n.output()

    (path,) = rec_dir.glob("*.mcap")
    with open(path, "rb") as fh:
        reader = make_reader(fh, decoder_factories=[DecoderFactory()])
        metas = [m.metadata for m in reader.iter_metadata() if m.name == "muscle_actuator"]
        states = [d for _, ch, _, d in reader.iter_decoded_messages() if ch.topic.endswith("/state")]
    # Written at start without an origin, again at the first /clock with it.
    assert [m["time_base"] for m in metas] == ["ros_clock", "ros_clock"], metas
    assert "tick_origin_ns" not in metas[0] and int(metas[1]["tick_origin_ns"]) == T0
    assert '"use_sim_time":true' in metas[1]["parameters_json"]
    assert states[-1].tick == k + 120
    assert all(ns(s.header.stamp) == T0 + s.tick * MS for s in states)
    r = subprocess.run(
        [NodeProcess.binary(), "replay", str(path), "--out", str(tmp_path / "again.mcap")],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    assert f"{len(states)} of {len(states)} recorded states reproduced bit for bit" in r.stderr, r.stderr


def test_a_clock_jump_back_is_reported_and_survived(peer, node_factory):
    n = node_factory(
        "/t_follow_jump", "-p", "use_sim_time:=true", "-p", "model:=hill", "-p", "record:=false",
    )
    f = Follower(peer, n)
    k = f.warm_up()
    f.tick_to(T0 + (k + 50) * MS, k + 50)
    # The simulator restarts: its clock goes back to 2 s.
    t1 = 2 * 10**9
    f.clock.publish(clock_msg(t1))
    wait_until(lambda: "/clock jumped back" in n.output(), 10.0, what="the jump reported")
    # Reset (inputs cleared), tick 0 at the new time: the node goes on from there.
    s = f.tick_to(t1 + 30 * MS, 30)
    assert ns(s.header.stamp) == t1 + 30 * MS
    assert [m.excitation for m in s.muscles] == [0.0, 0.0]
    assert n.alive()
    out = n.output()
    assert "from 5000." in out and "to 2.000000 s" in out, out[-2000:]
    # A time before zero is refused, and changes nothing.
    f.clock.publish(Clock(clock=Time(sec=-5, nanosec=0)))
    wait_until(lambda: "before zero" in n.output(), 10.0, what="the negative time refused")
    s = f.tick_to(t1 + 31 * MS, 31)
    assert ns(s.header.stamp) == t1 + 31 * MS
