"""A stop by signal never costs the recording: SIGINT and SIGTERM stops in a row, at random
moments (a quarter of them during start-up), half of them under a command flood and half of them
delivered twice within 5 ms (as `timeout` or a terminal's Ctrl-C through a wrapper script deliver
a signal to the process group as well): each exits 0 within a second and leaves a file that a
strict MCAP reader accepts whole.

MUSCLE_ACTUATOR_STOPS sets the number of stops per signal (default 100)."""

import os
import random
import signal
import subprocess
import threading
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader
from mcap.stream_reader import StreamReader
from mcap.records import Footer, Message
from muscle_actuator_msgs.msg import ActivationCommand

from helpers import NodeProcess, doctor, wait_until

STOPS = int(os.environ.get("MUSCLE_ACTUATOR_STOPS", "100"))
MAGIC = b"\x89MCAP0\r\n"


def strict_read(path):
    """The whole file, strictly: both magics, every record in sequence up to the footer, a summary
    whose statistics and chunk indexes agree with the messages. Returns the message count."""
    data = Path(path).read_bytes()
    assert data[:8] == MAGIC and data[-8:] == MAGIC, f"{path}: no end magic ({len(data)} bytes)"
    streamed = 0
    footer = False
    for record in StreamReader(open(path, "rb"), skip_magic=False).records:
        if isinstance(record, Message):
            streamed += 1
        footer = footer or isinstance(record, Footer)
    assert footer, f"{path}: no footer"
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        assert summary is not None and summary.statistics is not None, f"{path}: no summary"
        indexed = sum(1 for _ in reader.iter_messages())
    assert streamed == indexed == summary.statistics.message_count, (streamed, indexed)
    return streamed


class Flood:
    """Publishes activation commands as fast as rclpy can while `on` is set."""

    def __init__(self, peer, topic):
        self.pub = peer.node.create_publisher(ActivationCommand, topic, 10)
        self.on = threading.Event()
        self.stop = False
        self.sent = 0
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        msg = ActivationCommand()
        msg.muscle = ["flexor", "extensor"]
        while not self.stop:
            if not self.on.wait(0.05):
                continue
            msg.excitation = [random.random(), random.random()]
            self.pub.publish(msg)
            self.sent += 1


@pytest.mark.timeout(1800)
def test_signal_stops_keep_the_recording(peer, tmp_path):
    rng = random.Random(20261122)
    flood = Flood(peer, "/t_stops/muscle_actuator/activation")
    slow = []
    try:
        for sig in (signal.SIGINT, signal.SIGTERM):
            for i in range(STOPS):
                flooded, twice = i % 2 == 1, i % 4 >= 2
                rec_dir = tmp_path / f"{sig.name}-{i}"
                node = NodeProcess(
                    "/t_stops", ["-p", f"record_dir:={rec_dir}", "--log-level", "warn"]
                )
                node.start()
                flood.on.set() if flooded else flood.on.clear()
                # A random moment: during start-up for a quarter of the stops, else once the
                # recording exists.
                if i % 4 != 2:
                    wait_until(lambda: any(rec_dir.glob("*.mcap")), 20.0, what="the recording")
                time.sleep(rng.uniform(0.0, 0.4))
                t0 = time.monotonic()
                node.proc.send_signal(sig)
                if twice:
                    # The second delivery, at once or within the first's shutdown: part of the
                    # same stop.
                    if i % 8 >= 6:
                        time.sleep(rng.uniform(0.0, 0.005))
                    if node.proc.poll() is None:
                        node.proc.send_signal(sig)
                try:
                    code = node.proc.wait(timeout=10.0)
                except subprocess.TimeoutExpired:
                    node.proc.kill()
                    pytest.fail(f"{sig.name} stop {i} hung:\n{node.output()[-2000:]}")
                took = time.monotonic() - t0
                flood.on.clear()
                what = f"{sig.name} stop {i} (flood {flooded}, twice {twice})"
                assert code == 0, f"{what}: exit {code}\n{node.output()[-2000:]}"
                if took > 1.0:
                    slow.append((what, round(took, 2)))
                files = list(rec_dir.glob("*.mcap"))
                assert len(files) == 1, f"{what}: {files}"
                strict_read(files[0])
                if i % 25 == 0:
                    doctor(files[0])
    finally:
        flood.stop = True
        flood.thread.join(timeout=5)
    print(f"{2 * STOPS} stops, {flood.sent} flood commands sent; over 1 s: {slow}")
    assert not slow, f"stops that took more than a second: {slow}"
