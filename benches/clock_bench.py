#!/usr/bin/env python3
"""Simulated-time benchmark (docs/time.md):

1. `clock:=sim` as fast as it can: the real-time factor (simulated over wall-clock seconds, read
   from /clock by an rclpy subscriber over DURATION s) for Hill and DM, with ~/state published
   every tick, every 10 ticks (100 Hz) and practically never, an rclpy subscriber on ~/state
   (reliable, or best effort with --best-effort) counting what it receives;
2. `clock:=lockstep`: the round trip of `~/step` (1 tick) from an rclpy client, beside the round
   trip of the same service type served by a second rclpy process, in the same run.

Run through benches/clock.sh (builds, sets up the venv, loopback-only network namespace).
"""

import argparse
import os
import signal
import statistics
import subprocess
import sys
import time

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "python"))

import rclpy  # noqa: E402
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy  # noqa: E402
from muscle_actuator_msgs.msg import ActuatorState  # noqa: E402
from muscle_actuator_msgs.srv import Step  # noqa: E402
from rosgraph_msgs.msg import Clock  # noqa: E402
from spun import SpunNode  # noqa: E402

RELIABLE = QoSProfile(reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST, depth=10)
BEST_EFFORT = QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, history=HistoryPolicy.KEEP_LAST, depth=10)
CLOCK_QOS = QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, history=HistoryPolicy.KEEP_LAST, depth=1)


def step_server():
    """A second rclpy process serving Step: the rclpy-to-rclpy reference."""
    rclpy.init()
    node = rclpy.create_node("bench_step_server")

    def serve(req, resp):
        resp.success = True
        resp.tick = req.ticks
        return resp

    node.create_service(Step, "/bench/step", serve)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, SystemExit):
        pass


def pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, max(0, int(round(q * (len(xs) - 1)))))]


def node(bin_, ns, *params):
    args = [bin_, "node", "--ros-args", "-r", f"__ns:={ns}", "-p", "record:=false"]
    for p in params:
        args += ["-p", p]
    return subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def wait(pred, what, timeout=30.0):
    end = time.monotonic() + timeout
    while not pred():
        if time.monotonic() > end:
            sys.exit(f"timed out waiting for {what}")
        time.sleep(0.01)


def sim_rtf(bin_, model, publish, duration, qos):
    ns = f"/bench_sim_{model}_{str(publish).replace('.', '_')}"
    proc = node(bin_, ns, "clock:=sim", f"model:={model}", f"publish_rate_hz:={publish}")
    peer = SpunNode("bench_sim_peer")
    last = {"clock": None, "states": 0}
    peer.node.create_subscription(Clock, "/clock", lambda m: last.__setitem__("clock", m.clock), CLOCK_QOS)

    def on_state(_m):
        last["states"] += 1

    peer.node.create_subscription(ActuatorState, f"{ns}/muscle_actuator/state", on_state, qos)
    try:
        wait(lambda: last["clock"] is not None, "/clock")
        time.sleep(1.0)
        c0, w0, s0 = last["clock"], time.monotonic(), last["states"]
        time.sleep(duration)
        c1, w1, s1 = last["clock"], time.monotonic(), last["states"]
        sim = (c1.sec - c0.sec) + (c1.nanosec - c0.nanosec) / 1e9
        return sim / (w1 - w0), (s1 - s0) / (w1 - w0)
    finally:
        peer.close()
        proc.send_signal(signal.SIGINT)
        proc.wait()


def round_trips(client, n):
    req = Step.Request()
    req.ticks = 1
    out = []
    for _ in range(n):
        t = time.perf_counter()
        fut = client.call_async(req)
        while not fut.done():
            time.sleep(0)
        out.append(time.perf_counter() - t)
        assert fut.result().success, fut.result().message
    return out


def lockstep_rtt(bin_, steps):
    proc = node(bin_, "/bench_lock", "clock:=lockstep", "model:=huxley")
    server = subprocess.Popen([sys.executable, __file__, "--step-server", "--bin", "-"])
    peer = SpunNode("bench_lock_peer")
    try:
        ours = peer.node.create_client(Step, "/bench_lock/muscle_actuator/step")
        theirs = peer.node.create_client(Step, "/bench/step")
        for c in (ours, theirs):
            if not c.wait_for_service(timeout_sec=30.0):
                sys.exit("a Step service did not appear")
        # Warm-up (matching, first samples), then interleaved blocks of 50.
        round_trips(ours, 50)
        round_trips(theirs, 50)
        a, b = [], []
        for _ in range(steps // 50):
            a += round_trips(ours, 50)
            b += round_trips(theirs, 50)
        return a, b
    finally:
        peer.close()
        server.send_signal(signal.SIGINT)
        proc.send_signal(signal.SIGINT)
        server.wait()
        proc.wait()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--duration", type=float, default=5.0)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--best-effort", action="store_true",
                    help="subscribe to ~/state best effort (default: reliable, as the node publishes)")
    ap.add_argument("--step-server", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.step_server:
        step_server()
        return
    rclpy.init()
    print(f"load average {os.getloadavg()[0]:.2f}")
    qos = BEST_EFFORT if a.best_effort else RELIABLE
    print(f"clock:=sim, as fast as possible, an rclpy subscriber on ~/state "
          f"({'best effort' if a.best_effort else 'reliable'}):")
    print(f"{'model':8} {'~/state':>16} {'real-time factor':>17} {'states/s received':>18}")
    for model in ("hill", "huxley"):
        for label, publish in (("every tick", 0.0), ("100 Hz (1/10)", 100.0), ("none", 0.001)):
            rtf, sps = sim_rtf(a.bin, model, publish, a.duration, qos)
            print(f"{model:8} {label:>16} {rtf:17.1f} {sps:18.0f}")
    ours, theirs = lockstep_rtt(a.bin, a.steps)
    print(f"clock:=lockstep, ~/step of 1 tick (DM), {len(ours)} calls each, interleaved:")
    for name, xs in (("our node", ours), ("rclpy -> rclpy", theirs)):
        print(f"  {name:15} p50 {1e3 * statistics.median(xs):.3f} ms  p99 {1e3 * pct(xs, 0.99):.3f} ms")
    print(f"  ratio of medians {statistics.median(ours) / statistics.median(theirs):.2f}")
    print(f"load average {os.getloadavg()[0]:.2f}")
    rclpy.shutdown()


if __name__ == "__main__":
    main()
