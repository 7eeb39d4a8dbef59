"""Fresh rclpy service clients in a process of their own, for test_services_fresh.py: Fast DDS
with its stock settings (no test profile: its writers repeat an unacknowledged sample only at
their heartbeat, every 3 s).

    python fresh_clients.py NODE_FQN --count N [--services reset,step] [--timeout S]

For each of N rounds and each service named, a new client: `wait_for_service` (after a line
"waiting" on stderr), then one call with no retry. Prints one JSON list on stdout: per call the service, whether it was found,
whether it was answered (and successfully), and the seconds from the call to the answer."""

import argparse
import json
import os
import sys
import time

import rclpy
from rclpy.executors import SingleThreadedExecutor
from std_srvs.srv import Trigger

from muscle_actuator_msgs.srv import Step


def request(service):
    if service == "reset":
        return Trigger, Trigger.Request()
    req = Step.Request()
    req.ticks = 1
    return Step, req


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fqn")
    ap.add_argument("--count", type=int, default=1)
    ap.add_argument("--services", default="reset")
    ap.add_argument("--timeout", type=float, default=10.0)
    ap.add_argument("--discovery-timeout", type=float, default=30.0)
    a = ap.parse_args()
    if os.environ.get("FASTDDS_DEFAULT_PROFILES_FILE"):
        sys.exit("fresh_clients.py runs with Fast DDS's stock settings: unset FASTDDS_DEFAULT_PROFILES_FILE")

    rclpy.init()
    node = rclpy.create_node(f"fresh_clients_{os.getpid()}")
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    calls = []
    try:
        for _ in range(a.count):
            for service in a.services.split(","):
                srv_type, req = request(service)
                client = node.create_client(srv_type, f"{a.fqn}/{service}")
                call = {"service": service, "found": False, "answered": False, "success": False,
                        "seconds": None}
                calls.append(call)
                # The caller may start the node now, so that it appears while we wait.
                print("waiting", file=sys.stderr, flush=True)
                if client.wait_for_service(timeout_sec=a.discovery_timeout):
                    call["found"] = True
                    t0 = time.monotonic()
                    fut = client.call_async(req)
                    executor.spin_until_future_complete(fut, timeout_sec=a.timeout)
                    if fut.done() and fut.result() is not None:
                        call["seconds"] = time.monotonic() - t0
                        call["answered"] = True
                        call["success"] = bool(fut.result().success)
                node.destroy_client(client)
    finally:
        print(json.dumps(calls), flush=True)
        executor.remove_node(node)
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
