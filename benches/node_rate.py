#!/usr/bin/env python3
"""Node-rate benchmark (docs/benchmarks.md, "The node"): the node at 1 kHz for DURATION s,
publishing ~/state every tick, with an rclpy client commanding at 100 Hz. Reports the node's
tick lateness p50/p99/max and missed ticks (from the node's own summary at exit), and the
command-to-state latency seen by the client, beside an rclpy-to-rclpy echo round trip measured
in the same run. With --foxglove on, a Foxglove client (tests/foxglove/stream_bench.mjs, the
app's own protocol client and decoder) subscribes to every channel of the live view, and its
latency from a tick's stamp to the state's arrival is reported too; --foxglove off runs the
node without the live view (foxglove_port 0).

Run through benches/node_rate.sh (builds, sets up the venv, loopback-only network namespace).
"""

import argparse
import glob
import socket
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "python"))

import rclpy  # noqa: E402
from rclpy.qos import QoSProfile, ReliabilityPolicy, HistoryPolicy  # noqa: E402
from muscle_actuator_msgs.msg import ActivationCommand, ActuatorState  # noqa: E402
from spun import SpunNode  # noqa: E402

QOS = QoSProfile(reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST, depth=100)


def echo_server():
    """A second rclpy process that sends back every command it receives."""
    rclpy.init()
    node = rclpy.create_node("bench_echo")
    pub = node.create_publisher(ActivationCommand, "/bench/echo_out", QOS)
    node.create_subscription(ActivationCommand, "/bench/echo_in", pub.publish, QOS)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, SystemExit):
        pass


def pct(xs, q):
    if not xs:
        return float("nan")
    xs = sorted(xs)
    return xs[min(len(xs) - 1, max(0, int(round(q * (len(xs) - 1)))))]


def summary(xs):
    return {
        "n": len(xs),
        "p50_ms": pct(xs, 0.5) * 1e3,
        "p99_ms": pct(xs, 0.99) * 1e3,
        "max_ms": max(xs) * 1e3 if xs else float("nan"),
        "mean_ms": statistics.fmean(xs) * 1e3 if xs else float("nan"),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--model", default="huxley")
    ap.add_argument("--rate", type=float, default=1000.0)
    ap.add_argument("--command-rate", type=float, default=100.0)
    ap.add_argument("--json", help="write the figures here too")
    ap.add_argument("--record", choices=["on", "off"], default="on",
                    help="record to MCAP (the node's default) or not, to compare the tick lateness")
    ap.add_argument("--foxglove", choices=["on", "off"], default="off",
                    help="a Foxglove client subscribed to every channel of the live view, or no live view")
    ap.add_argument("--echo-server", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.echo_server:
        return echo_server()

    env = dict(os.environ, MUSCLE_ACTUATOR_TICK_SUMMARY="1")
    a.record_dir = tempfile.mkdtemp(prefix="node_rate_")
    a.port = free_port() if a.foxglove == "on" else 0
    node_proc = subprocess.Popen(
        [a.bin, "node", "--ros-args", "-r", "__ns:=/bench", "-p", f"model:={a.model}",
         "-p", f"rate_hz:={float(a.rate)}", "-p", f"record:={'true' if a.record == 'on' else 'false'}",
         "-p", f"record_dir:={a.record_dir}", "-p", f"foxglove_port:={a.port}", "--log-level", "error"],
        stderr=subprocess.PIPE, text=True, env=env,
    )
    echo_proc = subprocess.Popen([sys.executable, __file__, "--bin", a.bin, "--echo-server"])
    try:
        run_client(a, node_proc, echo_proc)
    finally:
        for p in (node_proc, echo_proc):
            if p.poll() is None:
                p.kill()


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_stream_client(a):
    """The Foxglove client of --foxglove on, subscribed to everything (connects once the node
    listens)."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "foxglove",
                          "stream_bench.mjs")
    end = time.monotonic() + 30
    while True:
        try:
            socket.create_connection(("127.0.0.1", a.port), timeout=1).close()
            break
        except OSError:
            if time.monotonic() > end:
                sys.exit("the live view never listened")
            time.sleep(0.1)
    return subprocess.Popen(["node", script, "--url", f"ws://127.0.0.1:{a.port}",
                             "--state", "/bench/muscle_actuator/state"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)


def stop_stream_client(proc):
    proc.send_signal(signal.SIGTERM)
    out, _ = proc.communicate(timeout=10)
    lines = [ln for ln in out.splitlines() if ln.startswith("{")]
    return json.loads(lines[-1]) if lines else {}


def thread_cpu_seconds(pid, name):
    """CPU time (user + system) of the process's threads called `name`, s."""
    total = 0
    for comm in glob.glob(f"/proc/{pid}/task/*/comm"):
        try:
            if open(comm).read().strip() != name:
                continue
            fields = open(comm[:-4] + "stat").read().rsplit(")", 1)[1].split()
            total += int(fields[11]) + int(fields[12])  # utime, stime (clock ticks)
        except OSError:
            pass
    return total / os.sysconf("SC_CLK_TCK")


def run_client(a, node_proc, echo_proc):
    rclpy.init()
    peer = SpunNode("bench_client")
    node = peer.node
    lock = threading.Lock()
    pending = {}  # excitation value -> send time (commands to the node)
    echo_pending = {}  # sequence -> send time
    lat, echo = [], []
    states = [0]

    def on_state(m):
        t = time.monotonic()
        states[0] += 1
        u = m.muscles[0].excitation
        with lock:
            t0 = pending.pop(u, None)
        if t0 is not None:
            lat.append(t - t0)

    def on_echo(m):
        t = time.monotonic()
        with lock:
            t0 = echo_pending.pop(m.header.stamp.nanosec, None)
        if t0 is not None:
            echo.append(t - t0)

    node.create_subscription(ActuatorState, "/bench/muscle_actuator/state", on_state, QOS)
    node.create_subscription(ActivationCommand, "/bench/echo_out", on_echo, QOS)
    cmd = node.create_publisher(ActivationCommand, "/bench/muscle_actuator/activation", QOS)
    echo_pub = node.create_publisher(ActivationCommand, "/bench/echo_in", QOS)

    def wait(pred, what, timeout=30.0):
        end = time.monotonic() + timeout
        while not pred():
            if time.monotonic() > end:
                sys.exit(f"timed out waiting for {what}")
            time.sleep(0.01)

    wait(lambda: cmd.get_subscription_count() > 0 and states[0] > 0, "the node")
    wait(lambda: echo_pub.get_subscription_count() > 0, "the echo server")
    stream = start_stream_client(a) if a.foxglove == "on" else None
    time.sleep(2.0)  # let both sides finish matching (first samples can be dropped)

    period = 1.0 / a.command_rate
    n = 0
    rec_cpu0 = thread_cpu_seconds(node_proc.pid, "recorder")
    t_start = time.monotonic()
    next_t = t_start
    sent = 0
    while time.monotonic() - t_start < a.duration:
        n += 1
        # A distinct excitation per command identifies the first state that carries it.
        u = 0.2 + (n % 1000) * 1e-4 + 1e-7
        m = ActivationCommand()
        m.muscle = ["flexor", "extensor"]
        m.excitation = [u, 0.2]
        e = ActivationCommand()
        e.header.stamp.nanosec = n
        now = time.monotonic()
        with lock:
            pending.clear()  # only the newest command is measured
            pending[u] = now
            echo_pending[n] = now
        cmd.publish(m)
        echo_pub.publish(e)
        sent += 1
        next_t += period
        time.sleep(max(0.0, next_t - time.monotonic()))
    time.sleep(0.5)
    wall = time.monotonic() - t_start
    live = stop_stream_client(stream) if stream else None
    rec_cpu = thread_cpu_seconds(node_proc.pid, "recorder") - rec_cpu0
    n_states = states[0]
    node_proc.send_signal(signal.SIGINT)
    _, err = node_proc.communicate(timeout=10)
    echo_proc.kill()  # rclpy.spin does not return on SIGTERM
    echo_proc.wait(timeout=10)
    peer.close()
    rclpy.try_shutdown()
    tick = {}
    for line in err.splitlines():
        if line.startswith("tick-summary: "):
            tick = json.loads(line[len("tick-summary: "):])
    expected_ticks = a.rate * wall
    res = {
        "model": a.model,
        "rate_hz": a.rate,
        "duration_s": round(wall, 2),
        "commands_sent": sent,
        "states_received": n_states,
        "tick": tick,
        "command_to_state": summary(lat),
        "rclpy_echo_round_trip": summary(echo),
        "record": a.record,
        "foxglove": a.foxglove,
    }
    if live is not None:
        res["live_view"] = live
    if a.record == "on":
        files = glob.glob(os.path.join(a.record_dir, "*.mcap"))
        size = sum(os.path.getsize(f) for f in files)
        res["recording"] = {"files": len(files), "bytes": size,
                            "bytes_per_s": size / wall if wall > 0 else float("nan"),
                            "recorder_thread_cpu_percent": 100.0 * rec_cpu / wall}
    t = tick
    print(f"node {a.model} at {a.rate:.0f} Hz for {wall:.1f} s, recording {a.record}, "
          f"live view {a.foxglove}; client commanding at {a.command_rate:.0f} Hz")
    if live:
        lat = live.get("state_latency_ms", {})
        print(f"  live view: {live.get('counts')}; tick stamp -> Foxglove client: n {lat.get('n')}, "
              f"p50 {lat.get('p50')} ms, p99 {lat.get('p99')} ms, max {lat.get('max')} ms")
    if "recording" in res:
        r = res["recording"]
        print(f"  recording: {r['bytes'] / 1e6:.2f} MB in {r['files']} file(s), {r['bytes_per_s'] / 1e3:.1f} kB per s; "
              f"recorder thread {r['recorder_thread_cpu_percent']:.2f}% of one core")
    if t:
        print(f"  ticks {t['ticks']} (about {expected_ticks:.0f} expected), ticks later than one period: "
              f"{t['overruns']}, skipped: {t['skipped']}")
        print(f"  tick lateness: p50 {t['p50_us']:.1f} us, p99 {t['p99_us']:.1f} us, max {t['max_us']:.1f} us; "
              f"mean step {t['mean_step_us']:.2f} us")
    else:
        print("  (no tick summary from the node)\n" + err[-2000:])
    for k, label in [("command_to_state", "command -> ~/state (rclpy -> node -> rclpy)"),
                     ("rclpy_echo_round_trip", "rclpy echo round trip (rclpy -> rclpy -> rclpy)")]:
        s = res[k]
        print(f"  {label}: n {s['n']}, p50 {s['p50_ms']:.3f} ms, p99 {s['p99_ms']:.3f} ms, "
              f"max {s['max_ms']:.3f} ms")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=2)
    ok = bool(t) and t["overruns"] == 0
    print(f"  bar (no tick later than one period): {'met' if ok else 'NOT met'}")


if __name__ == "__main__":
    main()
