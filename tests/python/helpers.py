"""Helpers for the rclpy tests: the node as a process, and an rclpy peer that waits for
matching (never for fixed sleeps) and collects messages."""

import math
import os
import signal
import subprocess
import tempfile
import threading
import time
from pathlib import Path

from rclpy.duration import Duration
from rclpy.parameter_client import AsyncParameterClient
from rclpy.qos import QoSProfile, ReliabilityPolicy, HistoryPolicy, DurabilityPolicy

from muscle_actuator_msgs.msg import ActivationCommand, ActuatorState, ExternalLoad
from sensor_msgs.msg import JointState
from diagnostic_msgs.msg import DiagnosticArray
from rcl_interfaces.msg import Log
from std_srvs.srv import Trigger

from spun import SpunNode

ROOT = Path(__file__).resolve().parents[2]

# Service calls: a first call is answered within milliseconds too (test_services_fresh.py); the
# margin is for a loaded machine.
SERVICE_TIMEOUT = 15.0
DISCOVERY_TIMEOUT = 20.0


def wait_until(predicate, timeout, interval=0.01, what="condition"):
    """Polls `predicate` until it is truthy; returns its value or raises AssertionError."""
    deadline = time.monotonic() + timeout
    while True:
        v = predicate()
        if v:
            return v
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(interval)


# Nodes run here, so that their default recordings (`runs/`) land in a scratch directory.
NODE_CWD = tempfile.mkdtemp(prefix="muscle_actuator_nodes_")


class NodeProcess:
    """`muscle_actuator node --ros-args -r __ns:=NS ...` as a child process."""

    def __init__(self, namespace, ros_args=(), env=None, name=None):
        self.namespace = namespace
        self.name = name or "muscle_actuator"
        self.ros_args = list(ros_args)
        self.env = dict(os.environ)
        if env:
            self.env.update(env)
        self.proc = None
        self.log = tempfile.NamedTemporaryFile(
            prefix=f"node{namespace.replace('/', '_')}_", suffix=".log", delete=False
        )
        self.returncode = None
        self.stop_seconds = None

    @staticmethod
    def binary():
        b = os.environ.get("MUSCLE_ACTUATOR_BIN")
        if b:
            return b
        return str(ROOT / "target" / "debug" / "muscle_actuator")

    @property
    def fqn(self):
        return (self.namespace.rstrip("/") + "/" + self.name) if self.namespace != "/" else "/" + self.name

    def topic(self, rel):
        """A name relative to the node: `~/x` (private) or `x` (in its namespace)."""
        if rel.startswith("~/"):
            return self.fqn + "/" + rel[2:]
        if rel.startswith("/"):
            return rel
        return (self.namespace.rstrip("/") + "/" + rel) if self.namespace != "/" else "/" + rel

    def command(self):
        args = [self.binary(), "node", "--ros-args"]
        # The live view (docs/live-view.md) listens on one port per host: nodes of the other
        # tests run without it, so that several can run at once; test_foxglove.py gives ports.
        if not any("foxglove_port" in a for a in self.ros_args):
            args += ["-p", "foxglove_port:=0"]
        if self.namespace != "/":
            args += ["-r", f"__ns:={self.namespace}"]
        if self.name != "muscle_actuator":
            args += ["-r", f"__node:={self.name}"]
        return args + self.ros_args

    def start(self):
        self.proc = subprocess.Popen(
            self.command(), stdout=self.log, stderr=subprocess.STDOUT, env=self.env, cwd=NODE_CWD
        )
        return self

    def alive(self):
        return self.proc is not None and self.proc.poll() is None

    def output(self):
        self.log.flush()
        return Path(self.log.name).read_text(errors="replace")

    def stop(self, sig=signal.SIGINT, timeout=5.0):
        """Sends `sig` and waits; records the exit code and how long the exit took."""
        if self.proc is None:
            return None
        if self.proc.poll() is None:
            t0 = time.monotonic()
            self.proc.send_signal(sig)
            try:
                self.proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
            self.stop_seconds = time.monotonic() - t0
        self.returncode = self.proc.returncode
        return self.returncode


def reliable(depth=10):
    return QoSProfile(
        reliability=ReliabilityPolicy.RELIABLE,
        history=HistoryPolicy.KEEP_LAST,
        depth=depth,
        durability=DurabilityPolicy.VOLATILE,
    )


class Inbox:
    """Messages of one subscription, collected on the executor thread."""

    def __init__(self):
        self.lock = threading.Lock()
        self.items = []  # (receive time, msg)

    def add(self, msg):
        with self.lock:
            self.items.append((time.monotonic(), msg))

    def msgs(self, since=None):
        with self.lock:
            return [m for (t, m) in self.items if since is None or t >= since]

    def timed(self, since=None):
        with self.lock:
            return [(t, m) for (t, m) in self.items if since is None or t >= since]

    def last(self):
        with self.lock:
            return self.items[-1][1] if self.items else None

    def clear(self):
        with self.lock:
            self.items.clear()

    def wait(self, predicate=lambda m: True, timeout=10.0, since=None, what="a message"):
        """The first message (received after `since`) that satisfies `predicate`."""

        def find():
            for m in self.msgs(since):
                if predicate(m):
                    return m
            return None

        return wait_until(find, timeout, what=what)


class Peer(SpunNode):
    """An rclpy node on its own executor thread, with the publishers, subscriptions and clients
    of the tests."""

    def __init__(self, name):
        super().__init__(name)
        self.subs = []
        self.pubs = {}
        self.clients = {}

    # --- graph -------------------------------------------------------------------------------
    def wait_for_node(self, name, namespace, timeout=DISCOVERY_TIMEOUT):
        return wait_until(
            lambda: (name, namespace) in self.node.get_node_names_and_namespaces(),
            timeout,
            what=f"node {namespace}/{name}",
        )

    # --- topics ------------------------------------------------------------------------------
    def subscribe(self, msg_type, topic, qos=None):
        inbox = Inbox()
        sub = self.node.create_subscription(msg_type, topic, inbox.add, qos or reliable())
        self.subs.append(sub)
        inbox.sub = sub
        return inbox

    def wait_matched_sub(self, inbox, timeout=DISCOVERY_TIMEOUT):
        wait_until(
            lambda: inbox.sub.get_publisher_count() > 0,
            timeout,
            what=f"a publisher on {inbox.sub.topic_name}",
        )

    def publisher(self, msg_type, topic, qos=None):
        key = (msg_type, topic)
        if key not in self.pubs:
            pub = self.node.create_publisher(msg_type, topic, qos or reliable())
            # Volatile messages sent before the match are lost: wait for it.
            wait_until(
                lambda: pub.get_subscription_count() > 0,
                DISCOVERY_TIMEOUT,
                what=f"a subscriber on {topic}",
            )
            self.pubs[key] = pub
        return self.pubs[key]

    def activation(self, topic, **excitations):
        msg = ActivationCommand()
        msg.header.stamp = self.node.get_clock().now().to_msg()
        msg.muscle = list(excitations.keys())
        msg.excitation = [float(v) for v in excitations.values()]
        self.publisher(ActivationCommand, topic).publish(msg)

    def activation_acked(self, topic, **excitations):
        """`activation`, then until the node has acknowledged it: in lockstep, the way to know
        that a command is at the node before the step request that follows it (DDS orders the
        samples of one writer, not those of a topic and a service; docs/time.md)."""
        self.activation(topic, **excitations)
        self.acked(self.publisher(ActivationCommand, topic))

    def acked(self, pub, timeout=10.0):
        """Until every reader matched to the reliable `pub` has acknowledged all it was sent."""
        assert pub.wait_for_all_acked(Duration(seconds=timeout)), \
            f"{pub.topic_name}: not acknowledged within {timeout} s"

    def raw_activation(self, topic, muscles, values):
        msg = ActivationCommand()
        msg.muscle = list(muscles)
        msg.excitation = [float(v) for v in values]
        self.publisher(ActivationCommand, topic).publish(msg)

    def load(self, topic, joints, torques):
        msg = ExternalLoad()
        msg.header.stamp = self.node.get_clock().now().to_msg()
        msg.joint = list(joints)
        msg.torque = [float(v) for v in torques]
        self.publisher(ExternalLoad, topic).publish(msg)

    # --- services ----------------------------------------------------------------------------
    def call(self, srv_type, name, request, timeout=SERVICE_TIMEOUT):
        key = (srv_type, name)
        if key not in self.clients:
            self.clients[key] = self.node.create_client(srv_type, name)
        client = self.clients[key]
        assert client.wait_for_service(timeout_sec=DISCOVERY_TIMEOUT), f"service {name} not found"
        fut = client.call_async(request)
        wait_until(fut.done, timeout, what=self._what(f"the answer of {name}"))
        return fut.result()

    def reset(self, node):
        return self.call(Trigger, node.topic("~/reset"), Trigger.Request())

    def param_client(self, node):
        key = ("params", node.fqn)
        if key not in self.clients:
            c = AsyncParameterClient(self.node, node.fqn)
            assert c.wait_for_services(timeout_sec=DISCOVERY_TIMEOUT), "parameter services not found"
            self.clients[key] = c
        return self.clients[key]

    def await_future(self, fut, timeout=SERVICE_TIMEOUT, what="a service answer"):
        wait_until(fut.done, timeout, what=self._what(what))
        return fut.result()


class Watch:
    """The usual subscriptions to one node: state, joint_states, diagnostics."""

    def __init__(self, peer, node, diagnostics=True, rosout=False):
        self.peer = peer
        self.node = node
        self.state = peer.subscribe(ActuatorState, node.topic("~/state"), reliable(100))
        self.joints = peer.subscribe(JointState, node.topic("joint_states"), reliable(100))
        self.diag = peer.subscribe(DiagnosticArray, "/diagnostics") if diagnostics else None
        self.rosout = None
        if rosout:
            self.rosout = peer.subscribe(
                Log,
                "/rosout",
                QoSProfile(
                    reliability=ReliabilityPolicy.RELIABLE,
                    history=HistoryPolicy.KEEP_LAST,
                    depth=1000,
                    durability=DurabilityPolicy.TRANSIENT_LOCAL,
                ),
            )
        peer.wait_matched_sub(self.state)
        peer.wait_matched_sub(self.joints)
        self.state.wait(timeout=DISCOVERY_TIMEOUT, what=f"{node.topic('~/state')}")

    def _until_seen(self, send, seen, timeout, what):
        """Sends an idempotent command until a state shows it (a first sample can be lost
        while RustDDS has not yet matched the new writer); returns the first such state."""
        deadline = time.monotonic() + timeout
        while True:
            t = time.monotonic()
            send()
            try:
                return self.state.wait(seen, timeout=0.5, since=t, what=what)
            except AssertionError:
                if time.monotonic() > deadline:
                    raise AssertionError(f"timed out after {timeout} s waiting for {what}")

    def activation(self, timeout=10.0, **u):
        """Commands excitations and waits until ~/state shows them in force."""
        topic = self.node.topic("~/activation")

        def seen(s):
            return all(
                abs(m.excitation - min(max(u[m.name], 0.0), 1.0)) < 1e-12
                for m in s.muscles
                if m.name in u
            )

        return self._until_seen(
            lambda: self.peer.activation(topic, **u), seen, timeout, f"excitation {u} in force"
        )

    def load(self, torque, timeout=10.0):
        """Applies an external torque and waits until ~/state shows it."""
        topic = self.node.topic("~/external_load")
        return self._until_seen(
            lambda: self.peer.load(topic, ["elbow"], [torque]),
            lambda s: s.external_torque[0] == torque,
            timeout,
            f"external torque {torque} in force",
        )

    def states_after(self, t0, duration):
        """The states received in [t0, t0 + duration] (waits until then)."""
        end = t0 + duration
        wait_until(lambda: time.monotonic() >= end, duration + 1.0)
        return [m for (t, m) in self.state.timed(t0) if t <= end]

    def next_state(self, predicate=lambda m: True, timeout=10.0, what="a state"):
        return self.state.wait(predicate, timeout=timeout, since=time.monotonic(), what=what)

    def diagnostics(self, since=None, timeout=5.0):
        """The next /diagnostics array of this node (as {status name suffix: {key: value}})."""
        return self.diagnostics_stamped(since, timeout)[1]

    def diagnostics_stamped(self, since=None, timeout=5.0):
        """The next /diagnostics array of this node, as (its header stamp in seconds, {status
        name suffix: {key: value}}): the stamp is the node's clock when it read its counters."""
        since = time.monotonic() if since is None else since
        fqn = self.node.fqn

        def mine(a):
            return any(s.hardware_id == fqn for s in a.status)

        arr = self.diag.wait(mine, timeout=timeout, since=since, what=f"/diagnostics of {fqn}")
        stamp = arr.header.stamp.sec + arr.header.stamp.nanosec * 1e-9
        out = {}
        for s in arr.status:
            if s.hardware_id == fqn:
                key = s.name.split(": ", 1)[-1]
                out[key] = {kv.key: kv.value for kv in s.values}
                out[key]["_level"] = int.from_bytes(s.level, "little") if isinstance(s.level, bytes) else int(s.level)
                out[key]["_message"] = s.message
        return stamp, out


def muscle(state, name):
    for m in state.muscles:
        if m.name == name:
            return m
    raise AssertionError(f"no muscle {name!r} in state (have {[m.name for m in state.muscles]})")


def finite_state(state):
    vals = list(state.position) + list(state.velocity) + list(state.torque) + list(state.stiffness)
    for m in state.muscles:
        vals += [m.force, m.activation, m.fiber_length, m.stiffness, m.q0, m.q1, m.q2]
    return all(math.isfinite(v) for v in vals)


def _proc_ip(hexaddr):
    """An address as /proc/net/udp{,6} prints it (32-bit words in host byte order)."""
    import socket
    import struct

    raw = b"".join(struct.pack("=I", int(hexaddr[i : i + 8], 16)) for i in range(0, len(hexaddr), 8))
    return socket.inet_ntop(socket.AF_INET if len(raw) == 4 else socket.AF_INET6, raw)


def udp_sockets(pid):
    """The UDP sockets process `pid` holds, as sorted (local address, port) pairs, read from
    /proc/PID/fd and /proc/PID/net/udp{,6} (the process's own network namespace)."""
    inodes = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        try:
            link = os.readlink(f"/proc/{pid}/fd/{fd}")
        except OSError:  # closed meanwhile
            continue
        if link.startswith("socket:["):
            inodes.add(link[len("socket:[") : -1])
    found = []
    for table in ("udp", "udp6"):
        path = Path(f"/proc/{pid}/net/{table}")
        if not path.exists():
            continue
        for line in path.read_text().splitlines()[1:]:
            f = line.split()
            if len(f) > 9 and f[9] in inodes:
                addr, port = f[1].split(":")
                found.append((_proc_ip(addr), int(port, 16)))
    return sorted(found)


def doctor(path):
    """`pymcap-cli doctor` (a GPL test tool, run as a program) finds no problem."""
    import sys
    exe = Path(sys.executable).parent / "pymcap-cli"
    r = subprocess.run([str(exe), "doctor", str(path)], capture_output=True, text=True)
    assert r.returncode == 0 and "passed MCAP doctor checks" in r.stdout, r.stdout + r.stderr
