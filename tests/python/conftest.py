"""Shared set-up for the rclpy tests: a real Fast DDS peer (rclpy) driving our RustDDS node.

Run through scripts/test-ros.sh (which builds the node and the Python environment and runs
this inside a loopback-only network namespace where it can). Discovery is always kept on this
host: ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST for rclpy, and the node defaults to loopback.
"""

import os
import random

# Before rclpy is imported: keep DDS on this host, use a domain of our own.
os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.pop("ROS_LOCALHOST_ONLY", None)
os.environ.setdefault("ROS_DOMAIN_ID", str(random.randint(100, 200)))
os.environ.setdefault("ROS_DISTRO", "kilted")
os.environ.setdefault(
    "FASTDDS_DEFAULT_PROFILES_FILE",
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "fastdds_profile.xml"),
)

import pytest  # noqa: E402
import rclpy  # noqa: E402

from helpers import NodeProcess, Peer  # noqa: E402


def pytest_report_header(config):
    return (
        f"ROS_DOMAIN_ID={os.environ['ROS_DOMAIN_ID']} "
        f"ROS_AUTOMATIC_DISCOVERY_RANGE={os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE']} "
        f"node binary={NodeProcess.binary()}"
    )


@pytest.fixture(scope="session")
def ros():
    """rclpy, once per session."""
    rclpy.init()
    yield
    rclpy.try_shutdown()


@pytest.fixture(scope="module")
def peer(ros, request):
    """An rclpy node spun on a background thread, one per test module."""
    name = "test_" + request.module.__name__.split(".")[-1].replace("test_", "")
    p = Peer(name)
    yield p
    p.close()


@pytest.fixture(scope="module")
def node_factory(request):
    """Starts node processes for a module and stops them (SIGINT) at its end."""
    started = []

    def start(namespace, *ros_args, **kw):
        n = NodeProcess(namespace, list(ros_args), **kw)
        n.start()
        started.append(n)
        return n

    yield start
    for n in started:
        n.stop()


@pytest.fixture
def short_lived():
    """Starts nodes for one test (as node_factory does for a module) and stops them at its end,
    so that they load no later test."""
    started = []

    def start(namespace, *ros_args, env=None):
        n = NodeProcess(namespace, list(ros_args), env=env).start()
        started.append(n)
        return n

    yield start
    for n in started:
        n.stop()
