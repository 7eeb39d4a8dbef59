"""Two nodes in two namespaces do not cross-talk; a node in another ROS_DOMAIN_ID is not seen."""

import os
import time

import pytest

from helpers import NodeProcess, Watch, muscle


@pytest.fixture(scope="module")
def pair(node_factory):
    a = node_factory("/t_iso_a", "-p", "model:=hill", "-p", "publish_rate_hz:=50.0")
    b = node_factory("/t_iso_b", "-p", "model:=hill", "-p", "publish_rate_hz:=50.0")
    return a, b


def test_commands_reach_only_their_node(peer, pair):
    a, b = pair
    wa = Watch(peer, a, diagnostics=False)
    wb = Watch(peer, b, diagnostics=False)
    wa.activation(flexor=0.9, extensor=0.0)
    t0 = time.monotonic()
    sa = wa.states_after(t0, 0.5)
    sb = [m for (t, m) in wb.state.timed(t0)]
    assert sb, "node b stopped publishing"
    assert muscle(sa[-1], "flexor").excitation == 0.9
    assert sa[-1].position[0] > 0.05
    assert all(muscle(s, "flexor").excitation == 0.0 for s in sb)
    assert all(abs(s.position[0]) < 1e-9 for s in sb)
    # And the other way round.
    wb.load(-3.0)
    s = wb.states_after(time.monotonic(), 0.3)[-1]
    assert s.position[0] < -0.05
    assert wa.next_state().external_torque[0] == 0.0


def test_another_domain_is_invisible(peer):
    other = str((int(os.environ["ROS_DOMAIN_ID"]) + 1) % 233)
    n = NodeProcess("/t_iso_domain", ["-p", "model:=hill"], env={"ROS_DOMAIN_ID": other})
    n.start()
    try:
        time.sleep(2.0)  # the absence of discovery can only be shown by waiting
        assert n.alive(), n.output()
        names = peer.node.get_node_names_and_namespaces()
        assert ("muscle_actuator", "/t_iso_domain") not in names
        topics = dict(peer.node.get_topic_names_and_types())
        assert "/t_iso_domain/muscle_actuator/state" not in topics
    finally:
        n.stop()
