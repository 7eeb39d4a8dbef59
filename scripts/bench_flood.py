#!/usr/bin/env python3
"""Flood benchmark: does a flood of valid commands stall the node's tick loop?

For each repetition, runs the node (release binary) twice or more -- a quiet window (no input)
and a flooded window (rclpy publishers at ACTIVATION_RATE on ~/activation and LOAD_RATE on
~/external_load, spread over several publisher processes that publish in paced batches) -- and
reports per window: the commands/s achieved (sent by the publishers, and received by the node
per its /diagnostics), ticks, skipped ticks, ticks later than one period, lateness p99 and max
(from the node's `tick-summary:` line at exit, MUSCLE_ACTUATOR_TICK_SUMMARY=1), the node's
"stalled" warnings, and the load average around the window.

Run through scripts/bench-flood.sh (release build, venv, loopback-only network namespace).
A benchmark, not a test: it asserts nothing.
"""

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.pop("ROS_LOCALHOST_ONLY", None)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "python"))

import rclpy  # noqa: E402
from rclpy.qos import QoSProfile, ReliabilityPolicy, HistoryPolicy, DurabilityPolicy  # noqa: E402
from muscle_actuator_msgs.msg import ActivationCommand, ExternalLoad  # noqa: E402
from diagnostic_msgs.msg import DiagnosticArray  # noqa: E402
from spun import SpunNode  # noqa: E402

NS = "/flood"
FQN = NS + "/muscle_actuator"
QOS = QoSProfile(
    reliability=ReliabilityPolicy.RELIABLE,
    history=HistoryPolicy.KEEP_LAST,
    depth=10,
    durability=DurabilityPolicy.VOLATILE,
)


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


# --- publisher child -----------------------------------------------------------------------


def publisher(a):
    """Publishes `a.kind` messages at `a.rate` from `a.start` (time.time()) for `a.duration` s,
    in batches paced by the clock (as many as are due every ~1 ms); prints the count sent."""
    rclpy.init()
    node = rclpy.create_node(f"flood_{a.kind}_{os.getpid()}")
    if a.kind == "activation":
        pub = node.create_publisher(ActivationCommand, FQN + "/activation", QOS)
        msgs = []
        for k in range(64):
            m = ActivationCommand()
            m.muscle = ["flexor", "extensor"]
            m.excitation = [0.2 + 0.3 * k / 64, 0.1]
            msgs.append(m)
    else:
        pub = node.create_publisher(ExternalLoad, FQN + "/external_load", QOS)
        msgs = []
        for k in range(64):
            m = ExternalLoad()
            m.joint = ["elbow"]
            m.torque = [0.1 * k / 64]
            msgs.append(m)
    end_match = time.monotonic() + 30
    while pub.get_subscription_count() == 0 and time.monotonic() < end_match:
        time.sleep(0.01)
    matched = pub.get_subscription_count() > 0
    delay = a.start - time.time()
    if delay > 0:
        time.sleep(delay)
    t0 = time.monotonic()
    sent = 0
    n = len(msgs)
    publish = pub.publish
    while True:
        el = time.monotonic() - t0
        if el >= a.duration:
            break
        due = int(a.rate * el) + 1
        while sent < due:
            publish(msgs[sent % n])
            sent += 1
        time.sleep(0.001)
    elapsed = time.monotonic() - t0
    print(json.dumps({"kind": a.kind, "sent": sent, "elapsed": elapsed, "matched": matched}),
          flush=True)
    node.destroy_node()
    rclpy.try_shutdown()


# --- orchestrator ---------------------------------------------------------------------------


class Diag:
    """Keeps the node's latest /diagnostics key-values (inputs, tick loop)."""

    def __init__(self, node):
        self.lock = threading.Lock()
        self.latest = {}
        self.count = 0
        node.create_subscription(DiagnosticArray, "/diagnostics", self.on_msg, QOS)

    def on_msg(self, msg):
        d = {}
        for st in msg.status:
            if not st.name.startswith(FQN + ":"):
                continue
            key = st.name.split(": ", 1)[1]
            d[key] = {kv.key: kv.value for kv in st.values}
        if d:
            with self.lock:
                self.latest = d
                self.count += 1

    def snapshot(self):
        with self.lock:
            return self.count, json.loads(json.dumps(self.latest))


def counter(d, block, key):
    try:
        return int(d[block][key])
    except (KeyError, ValueError):
        return 0


def run_window(a, diag, window, rep):
    env = dict(os.environ, MUSCLE_ACTUATOR_TICK_SUMMARY="1")
    log = tempfile.NamedTemporaryFile(prefix=f"flood_{window}_{rep}_", suffix=".log", delete=False)
    cmd = [a.bin, "node", "--ros-args", "-r", f"__ns:={NS}", "-p", f"model:={a.model}",
           "-p", f"record:={'true' if a.record == 'on' else 'false'}",
           "-p", f"record_dir:={a.record_dir}", "--log-level", "warn"]
    node_proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    c0, _ = diag.snapshot()
    end = time.monotonic() + 30
    while diag.snapshot()[0] < c0 + 2:
        if time.monotonic() > end or node_proc.poll() is not None:
            node_proc.kill()
            sys.exit(f"the node did not come up (log: {log.name})")
        time.sleep(0.05)
    pubs = []
    lead = 0.0
    if window == "flood":
        lead = 4.0  # publisher processes start, discover and match before the common start
        start = time.time() + lead
        shares = [("activation", a.activation_rate / a.publishers)] * a.publishers
        if a.load_rate > 0:
            shares.append(("load", a.load_rate))
        for kind, rate in shares:
            pubs.append(subprocess.Popen(
                [sys.executable, __file__, "--publisher", kind, "--rate", str(rate),
                 "--start", str(start), "--duration", str(a.duration)],
                stdout=subprocess.PIPE, text=True))
        time.sleep(max(0.0, start - time.time()))
    load_before = loadavg()
    _, d0 = diag.snapshot()
    t0 = time.monotonic()
    if pubs:
        outs = [p.communicate(timeout=a.duration + 60)[0] for p in pubs]
    else:
        time.sleep(a.duration)
        outs = []
    wall = time.monotonic() - t0
    time.sleep(1.5)  # a last /diagnostics with the window's counts
    _, d1 = diag.snapshot()
    load_after = loadavg()
    node_proc.send_signal(signal.SIGINT)
    try:
        node_proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        node_proc.kill()
        node_proc.wait()
    log.flush()
    text = open(log.name, errors="replace").read()
    tick = {}
    stalls = []
    for line in text.splitlines():
        if line.startswith("tick-summary: "):
            tick = json.loads(line[len("tick-summary: "):])
        if "ticks skipped" in line:
            stalls.append(line.split("]: ", 1)[-1])
    sent = {"activation": 0, "load": 0}
    pub_s = {"activation": 0.0, "load": 0.0}
    for o in outs:
        for line in o.splitlines():
            if line.startswith("{"):
                r = json.loads(line)
                sent[r["kind"]] += r["sent"]
                pub_s[r["kind"]] = max(pub_s[r["kind"]], r["elapsed"])
    recv_act = counter(d1, "inputs", "activation_received") - counter(d0, "inputs", "activation_received")
    recv_load = counter(d1, "inputs", "load_received") - counter(d0, "inputs", "load_received")
    res = {
        "window": window, "rep": rep, "duration_s": round(wall, 2),
        "sent_activation_hz": sent["activation"] / max(pub_s["activation"], 1e-9) if pubs else 0.0,
        "sent_load_hz": sent["load"] / max(pub_s["load"], 1e-9) if a.load_rate > 0 and pubs else 0.0,
        # Received over the diagnostics interval (window + ~1.5 s tail, 1 Hz sampling).
        "recv_activation_hz": recv_act / wall,
        "recv_load_hz": recv_load / wall,
        "commands_dropped": counter(d1, "tick loop", "commands_dropped"),
        "commands_deferred": counter(d1, "tick loop", "commands_deferred"),
        "states_dropped": counter(d1, "tick loop", "states_dropped"),
        "applied_inputs_dropped": counter(d1, "tick loop", "applied_inputs_dropped"),
        "realtime": d1.get("tick loop", {}).get("realtime_priority", "?"),
        "tick": tick, "stalls": stalls, "load_before": load_before, "load_after": load_after,
        "log": log.name,
    }
    if not tick:
        res["log_tail"] = text[-1500:]
    return res


def fmt_row(r):
    t = r["tick"] or {}
    return (f"{r['window']:<6} {r['rep']:>3} {r['sent_activation_hz']:>9.0f} {r['sent_load_hz']:>7.0f} "
            f"{r['recv_activation_hz']:>9.0f} {r['recv_load_hz']:>7.0f} {t.get('ticks', -1):>7} "
            f"{t.get('skipped', -1):>7} {t.get('overruns', -1):>8} {t.get('p99_us', float('nan')):>9.1f} "
            f"{t.get('max_us', float('nan')) / 1e3:>9.2f} {r['commands_dropped']:>8} {r['commands_deferred']:>6} "
            f"{r['states_dropped']:>6}  "
            f"{r['load_before']} -> {r['load_after']}  rt={r['realtime']}")


HEADER = (f"{'window':<6} {'rep':>3} {'act_tx/s':>9} {'ld_tx/s':>7} {'act_rx/s':>9} {'ld_rx/s':>7} "
          f"{'ticks':>7} {'skipped':>7} {'overruns':>8} {'p99_us':>9} {'max_ms':>9} {'cmd_drop':>8} {'defer':>6} "
          f"{'st_drop':>6}  "
          f"loadavg before -> after")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin")
    ap.add_argument("--runs", type=int, default=5, help="repetitions of each window")
    ap.add_argument("--duration", type=float, default=10.0, help="window length, s")
    ap.add_argument("--model", default="huxley")
    ap.add_argument("--record", choices=["on", "off"], default="off")
    ap.add_argument("--activation-rate", type=float, default=15000.0, help="total, Hz")
    ap.add_argument("--load-rate", type=float, default=2000.0, help="Hz")
    ap.add_argument("--publishers", type=int, default=3, help="activation publisher processes")
    ap.add_argument("--windows", default="quiet,flood", help="order within a repetition")
    ap.add_argument("--json", help="write all results here too")
    # child mode
    ap.add_argument("--publisher", choices=["activation", "load"], help=argparse.SUPPRESS)
    ap.add_argument("--rate", type=float, help=argparse.SUPPRESS)
    ap.add_argument("--start", type=float, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.publisher:
        a.kind = a.publisher
        return publisher(a)
    if not a.bin:
        sys.exit("--bin is required")
    a.record_dir = tempfile.mkdtemp(prefix="bench_flood_")

    rclpy.init()
    peer = SpunNode("bench_flood")
    diag = Diag(peer.node)

    print(f"# bench_flood: {a.bin}")
    print(f"# model {a.model}, 1 kHz, recording {a.record}; windows of {a.duration:.0f} s x {a.runs}; "
          f"flood: {a.activation_rate:.0f} Hz activation over {a.publishers} processes + "
          f"{a.load_rate:.0f} Hz load; {os.cpu_count()} CPUs", flush=True)
    print(f"# uptime at start: {subprocess.run(['uptime'], capture_output=True, text=True).stdout.strip()}")
    print(HEADER, flush=True)
    results = []
    for rep in range(1, a.runs + 1):
        for w in a.windows.split(","):
            r = run_window(a, diag, w, rep)
            results.append(r)
            print(fmt_row(r), flush=True)
            for s in r["stalls"]:
                print(f"       stall: {s}", flush=True)
            if "log_tail" in r:
                print(r["log_tail"], flush=True)
    print(f"# uptime at end: {subprocess.run(['uptime'], capture_output=True, text=True).stdout.strip()}")
    print("# totals per window:")
    for w in a.windows.split(","):
        rs = [r for r in results if r["window"] == w and r["tick"]]
        if not rs:
            continue
        sk = [r["tick"]["skipped"] for r in rs]
        print(f"#   {w}: {len(rs)} runs, runs with skipped ticks: {sum(1 for s in sk if s > 0)}, "
              f"skipped total {sum(sk)}, max skipped {max(sk)}, overruns total "
              f"{sum(r['tick']['overruns'] for r in rs)}, worst p99 "
              f"{max(r['tick']['p99_us'] for r in rs):.1f} us, worst max "
              f"{max(r['tick']['max_us'] for r in rs) / 1e3:.2f} ms, mean activation sent "
              f"{sum(r['sent_activation_hz'] for r in rs) / len(rs):.0f}/s received "
              f"{sum(r['recv_activation_hz'] for r in rs) / len(rs):.0f}/s")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=2)
    peer.close()
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
