#!/usr/bin/env python3
"""rclpy demo client: sweeps co-contraction (both muscles at the same excitation) and prints
the joint stiffness the node reports on ~/state.

    .venv/bin/python launch-scripts/cocontraction_sweep.py [--node /muscle_actuator]
                     [--levels 0,0.1,0.2,...] [--settle 0.5]

Start the node first (launch-scripts/run-node.sh, or launch-scripts/demo.sh for both).
"""

import argparse
import os
import sys
import threading
import time

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")

import rclpy  # noqa: E402
from rclpy.executors import SingleThreadedExecutor  # noqa: E402
from rclpy.qos import QoSProfile, ReliabilityPolicy, HistoryPolicy  # noqa: E402
from std_srvs.srv import Trigger  # noqa: E402
from muscle_actuator_msgs.msg import ActivationCommand, ActuatorState  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--node", default="/muscle_actuator", help="the node's full name")
    ap.add_argument("--levels", default="0,0.05,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0")
    ap.add_argument("--settle", type=float, default=0.5, help="seconds to settle at each level")
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds to wait for the node")
    a = ap.parse_args()
    levels = [float(x) for x in a.levels.split(",") if x.strip()]
    if any(not 0.0 <= u <= 1.0 for u in levels):
        sys.exit("levels must lie in [0, 1]")

    rclpy.init()
    node = rclpy.create_node("cocontraction_sweep")
    qos = QoSProfile(reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST, depth=10)
    lock = threading.Lock()
    latest = {}

    def on_state(m):
        with lock:
            latest["s"] = m

    node.create_subscription(ActuatorState, f"{a.node}/state", on_state, qos)
    pub = node.create_publisher(ActivationCommand, f"{a.node}/activation", qos)
    ex = SingleThreadedExecutor()
    ex.add_node(node)
    spin = threading.Thread(target=ex.spin, daemon=True)
    spin.start()

    def wait(pred, timeout, what):
        end = time.monotonic() + timeout
        while not pred():
            if time.monotonic() > end:
                sys.exit(f"timed out waiting for {what}")
            time.sleep(0.01)

    wait(lambda: pub.get_subscription_count() > 0 and "s" in latest, a.timeout, f"{a.node}")
    reset = node.create_client(Trigger, f"{a.node}/reset")
    if reset.wait_for_service(timeout_sec=a.timeout):
        f = reset.call_async(Trigger.Request())
        wait(f.done, 15.0, "the reset answer")

    with lock:
        first = latest["s"]
    names = [m.name for m in first.muscles]
    print(f"node {a.node}: model {first.model}, joint {first.joint[0]}, muscles {', '.join(names)}")
    print(f"{'u (both)':>9} {'stiffness N m/rad':>18} {'angle rad':>10} {'force ' + names[0] + ' N':>16} {'force ' + names[1] + ' N':>16}")
    for u in levels:
        msg = ActivationCommand()
        msg.muscle = names
        msg.excitation = [u] * len(names)
        t0 = time.monotonic()
        # Re-send until it shows (a first sample may be lost right after discovery).
        while True:
            msg.header.stamp = node.get_clock().now().to_msg()
            pub.publish(msg)
            time.sleep(0.1)
            with lock:
                s = latest["s"]
            if all(abs(m.excitation - u) < 1e-12 for m in s.muscles):
                break
            if time.monotonic() - t0 > a.timeout:
                sys.exit("the node does not take the command")
        time.sleep(a.settle)
        with lock:
            s = latest["s"]
        print(f"{u:9.2f} {s.stiffness[0]:18.2f} {s.position[0]:10.4f} {s.muscles[0].force:16.1f} {s.muscles[1].force:16.1f}")
    # The spin thread ends before the node and the context go (rclpy aborts the process when the
    # context is shut down under a running executor).
    ex.shutdown()
    spin.join(timeout=5.0)
    node.destroy_node()
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
