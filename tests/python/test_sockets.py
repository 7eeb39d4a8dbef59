"""Nothing from outside unless asked: with a local discovery scope (the default,
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST, ROS_LOCALHOST_ONLY=1) every UDP socket of the node is
bound to loopback, so no other host can send it DDS traffic; discovery with rclpy still works.
Only ROS_AUTOMATIC_DISCOVERY_RANGE=SUBNET may bind all interfaces."""

import pytest

from helpers import NodeProcess, Watch, udp_sockets

LOOPBACK = {"127.0.0.1", "::1"}

# (case, variables set, variables removed) on top of the test environment.
LOCAL_SCOPES = [
    ("default", {}, ["ROS_AUTOMATIC_DISCOVERY_RANGE", "ROS_LOCALHOST_ONLY"]),
    ("range_localhost", {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}, ["ROS_LOCALHOST_ONLY"]),
    ("localhost_only", {"ROS_LOCALHOST_ONLY": "1"}, ["ROS_AUTOMATIC_DISCOVERY_RANGE"]),
]


def start(namespace, set_env, unset_env):
    n = NodeProcess(namespace, ["-p", "model:=hill", "-p", "publish_rate_hz:=50.0"], env=set_env)
    for k in unset_env:
        n.env.pop(k, None)
    return n.start()


def show(case, node):
    socks = udp_sockets(node.proc.pid)
    print(f"\n[{case}] UDP sockets of {node.fqn} (pid {node.proc.pid}):")
    for addr, port in socks:
        print(f"    {addr}:{port}")
    return socks


@pytest.mark.parametrize("case,set_env,unset_env", LOCAL_SCOPES, ids=[c[0] for c in LOCAL_SCOPES])
def test_local_scope_binds_only_loopback(peer, case, set_env, unset_env):
    ns = f"/t_sockets_{case}"
    n = start(ns, set_env, unset_env)
    try:
        # Discovery works both ways over the loopback-bound sockets: rclpy sees the node and
        # its topics, and a command from rclpy reaches it.
        peer.wait_for_node("muscle_actuator", ns)
        w = Watch(peer, n, diagnostics=False)
        w.activation(flexor=0.5)
        assert n.alive(), n.output()
        socks = show(case, n)
        assert socks, "the node holds no UDP socket"
        wildcard = [s for s in socks if s[0] in ("0.0.0.0", "::")]
        assert not wildcard, f"sockets bound to all interfaces: {wildcard}"
        assert all(addr in LOOPBACK for addr, _ in socks), socks
    finally:
        n.stop()


def test_subnet_scope_may_bind_all_interfaces(peer):
    ns = "/t_sockets_subnet"
    n = start(ns, {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}, ["ROS_LOCALHOST_ONLY"])
    try:
        peer.wait_for_node("muscle_actuator", ns)
        assert n.alive(), n.output()
        show("subnet", n)  # listed, not asserted: all interfaces were asked for
    finally:
        n.stop()
