"""Discovery through rclpy's graph API: node, topics with their types, services, under the
namespace given by `-r __ns:=`; logging reaches /rosout."""

import pytest
from helpers import DISCOVERY_TIMEOUT, Watch, wait_until

NS = "/t_graph/arm"


@pytest.fixture(scope="module")
def node(node_factory):
    return node_factory(NS, "-p", "publish_rate_hz:=50.0", "-p", "model:=hill")


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node, rosout=True)


def test_node_is_visible_under_its_namespace(peer, node):
    peer.wait_for_node("muscle_actuator", NS)
    assert ("muscle_actuator", "/") not in peer.node.get_node_names_and_namespaces()


def test_topics_and_types(peer, node, watch):
    expected = {
        f"{NS}/muscle_actuator/activation": "muscle_actuator_msgs/msg/ActivationCommand",
        f"{NS}/muscle_actuator/external_load": "muscle_actuator_msgs/msg/ExternalLoad",
        f"{NS}/muscle_actuator/state": "muscle_actuator_msgs/msg/ActuatorState",
        f"{NS}/joint_states": "sensor_msgs/msg/JointState",
        "/diagnostics": "diagnostic_msgs/msg/DiagnosticArray",
    }

    def all_there():
        topics = dict(peer.node.get_topic_names_and_types())
        return all(expected[t] in topics.get(t, []) for t in expected)

    wait_until(all_there, DISCOVERY_TIMEOUT, what="the node's topics")
    # Who publishes and who subscribes, by node.
    pubs = peer.node.get_publisher_names_and_types_by_node("muscle_actuator", NS)
    subs = peer.node.get_subscriber_names_and_types_by_node("muscle_actuator", NS)
    pub_names = {n for n, _ in pubs}
    sub_names = {n for n, _ in subs}
    assert {f"{NS}/muscle_actuator/state", f"{NS}/joint_states", "/diagnostics"} <= pub_names
    assert {f"{NS}/muscle_actuator/activation", f"{NS}/muscle_actuator/external_load"} <= sub_names
    # QoS of the inputs: reliable (docs/ros-interface.md), so rclpy's default publishers are matched.
    info = peer.node.get_subscriptions_info_by_topic(f"{NS}/muscle_actuator/activation")
    assert info, "no subscription info"
    assert all(i.qos_profile.reliability.name == "RELIABLE" for i in info)


def test_services(peer, node):
    expected = {
        f"{NS}/muscle_actuator/reset": "std_srvs/srv/Trigger",
        f"{NS}/muscle_actuator/get_parameters": "rcl_interfaces/srv/GetParameters",
        f"{NS}/muscle_actuator/set_parameters": "rcl_interfaces/srv/SetParameters",
        f"{NS}/muscle_actuator/list_parameters": "rcl_interfaces/srv/ListParameters",
        f"{NS}/muscle_actuator/describe_parameters": "rcl_interfaces/srv/DescribeParameters",
        f"{NS}/muscle_actuator/get_parameter_types": "rcl_interfaces/srv/GetParameterTypes",
        f"{NS}/muscle_actuator/set_parameters_atomically": "rcl_interfaces/srv/SetParametersAtomically",
    }

    def all_there():
        services = dict(peer.node.get_service_names_and_types())
        return all(expected[s] in services.get(s, []) for s in expected)

    wait_until(all_there, DISCOVERY_TIMEOUT, what="the node's services")


def test_state_arrives_and_names_the_configuration(watch):
    s = watch.state.wait(timeout=DISCOVERY_TIMEOUT)
    assert s.model == "hill"
    assert list(s.joint) == ["elbow"]
    assert [m.name for m in s.muscles] == ["flexor", "extensor"]
    assert s.tick > 0
    js = watch.joints.wait(timeout=DISCOVERY_TIMEOUT)
    assert list(js.name) == ["elbow"]


def test_rosout_carries_the_node_log(watch, peer, node):
    # The start-up line is published before we subscribed; a rejected command makes a fresh one.
    peer.raw_activation(node.topic("~/activation"), ["biceps"], [0.5])
    m = watch.rosout.wait(
        lambda m: "biceps" in m.msg,
        timeout=DISCOVERY_TIMEOUT,
        what="a /rosout line about the rejected command",
    )
    assert m.level == 30  # WARN
    assert "muscle_actuator" in m.name
