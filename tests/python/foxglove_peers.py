"""The peers of the live view's tests (test_foxglove.py, test_foxglove_hostile.py), as a plain
module: the Foxglove app's own client under Node.js (tests/foxglove/client.mjs), a raw WebSocket
client for what a library would not send, a reader of a recording as it grows, and the small
helpers they share: free ports and the sockets a node listens on, its memory, its log, and the
comparison of an rclpy message with the Foxglove decoder's JSON of it."""

import array
import base64
import hashlib
import json
import os
import re
import shutil
import socket
import struct
import subprocess
import threading
import time
from io import BytesIO
from pathlib import Path

import pytest
from mcap.data_stream import ReadDataStream
from mcap.opcode import Opcode
from mcap.records import Channel, Chunk, Message, Schema
from mcap.stream_reader import breakup_chunk
from mcap_ros2.decoder import DecoderFactory
from rclpy.parameter import parameter_value_to_python

from helpers import ROOT, _proc_ip, muscle, wait_until

FOXGLOVE_DIR = ROOT / "tests" / "foxglove"
CLIENT = FOXGLOVE_DIR / "client.mjs"
SUBPROTOCOLS = ("foxglove.sdk.v1", "foxglove.websocket.v1")
SEPARATOR = re.compile(r"^=+\s*$", re.M)

needs_node = pytest.mark.skipif(
    shutil.which("node") is None,
    reason="node (Node.js) is not on PATH: the Foxglove client is a Node.js program",
)


def require_client():
    """For a module-scoped autouse fixture: its tests fail, not skip, without tests/foxglove's
    packages."""
    if not (FOXGLOVE_DIR / "node_modules" / "@foxglove" / "ws-protocol").is_dir():
        pytest.fail("tests/foxglove has no node_modules: run `npm ci` there (scripts/test-ros.sh does)")


# --- the Node.js client -------------------------------------------------------------------------


class FoxgloveClient:
    """tests/foxglove/client.mjs as a child process: JSON commands in, JSON events out (read on a
    thread). Every wait has a timeout and names what it waited for."""

    def __init__(self, port, subprotocol="foxglove.sdk.v1"):
        self.proc = subprocess.Popen(
            ["node", str(CLIENT), "--url", f"ws://127.0.0.1:{port}", "--subprotocol", subprotocol],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
            text=True, bufsize=1, cwd=FOXGLOVE_DIR,
        )
        self._events = []
        self._ended = False
        self._stderr = []
        self._cond = threading.Condition()
        threading.Thread(target=self._read_events, daemon=True).start()
        threading.Thread(target=self._read_stderr, daemon=True).start()

    def _read_events(self):
        for line in self.proc.stdout:
            try:
                event = json.loads(line)
            except ValueError:
                event = {"event": "unparsed", "line": line}
            with self._cond:
                self._events.append(event)
                self._cond.notify_all()
        with self._cond:
            self._ended = True
            self._cond.notify_all()

    def _read_stderr(self):
        for line in self.proc.stderr:
            self._stderr.append(line)

    def _context(self):
        return f"client stderr: {''.join(self._stderr)[-1500:]!r}"

    def send(self, cmd, **fields):
        line = json.dumps({"cmd": cmd, **fields}, allow_nan=False)
        try:
            self.proc.stdin.write(line + "\n")
            self.proc.stdin.flush()
        except (BrokenPipeError, ValueError):
            raise AssertionError(f"the client has ended; cannot send {cmd} ({self._context()})")

    def mark(self):
        """A position in the event list: a wait or a listing `since` it sees only later events."""
        with self._cond:
            return len(self._events)

    def events(self, kind, since=0):
        with self._cond:
            return [e for e in self._events[since:] if e.get("event") == kind]

    def history(self, since=0):
        """Every event at or after `since`, in the order they came."""
        with self._cond:
            return list(self._events[since:])

    def wait(self, kind, predicate=lambda e: True, timeout=10.0, since=0, what=None):
        """The first event `kind` at or after `since` that satisfies `predicate`."""
        what = what or f"a {kind!r} event"
        deadline = time.monotonic() + timeout
        with self._cond:
            at = since
            while True:
                for e in self._events[at:]:
                    if e.get("event") == kind and predicate(e):
                        return e
                at = len(self._events)
                left = deadline - time.monotonic()
                if self._ended or left <= 0:
                    why = "the client ended" if self._ended else f"timed out after {timeout} s"
                    raise AssertionError(f"{why} waiting for {what} ({self._context()})")
                self._cond.wait(left)

    def wait_count(self, kind, n, topic=None, timeout=10.0, since=0):
        """At least `n` events `kind` (of `topic`) at or after `since`, the first `n` of them."""
        def enough():
            got = [e for e in self.events(kind, since) if topic is None or e.get("topic") == topic]
            return got[:n] if len(got) >= n else None

        return wait_until(enough, timeout, what=f"{n} {kind!r} events {topic or ''}")

    # --- the session -------------------------------------------------------------------------
    def connected(self, timeout=15.0):
        """serverInfo and the channels; returns (serverInfo, {topic: channel})."""
        info = self.wait("serverInfo", timeout=timeout)
        advertised = self.wait("advertise", timeout=timeout)
        return info, {c["topic"]: c for c in advertised["channels"]}

    def services(self, timeout=15.0):
        return {s["name"]: s for s in self.wait("advertiseServices", timeout=timeout)["services"]}

    def subscribe(self, topic, max=None, raw=False):
        self.send("subscribe", topic=topic, max=max, raw=raw)

    def count(self, topic, timeout=5.0):
        since = self.mark()
        self.send("count", topic=topic)
        return self.wait("count", lambda e: e["topic"] == topic, timeout, since)["n"]

    def advertise(self, topic, encoding, schema_name):
        since = self.mark()
        self.send("advertise", topic=topic, encoding=encoding, schemaName=schema_name)
        self.wait("advertised", lambda e: e["topic"] == topic, 5.0, since)

    def publish(self, topic, message):
        since = self.mark()
        self.send("publish", topic=topic, message=message)
        self.wait("published", lambda e: e["topic"] == topic, 5.0, since)

    def call(self, service, request, timeout=15.0):
        """A service call: the serviceResponse (or serviceFailure) event."""
        since = self.mark()
        self.send("callService", service=service, request=request, encoding="cdr")
        call_id = self.wait("called", lambda e: e["service"] == service, 5.0, since)["callId"]
        deadline = time.monotonic() + timeout
        while True:
            for kind in ("serviceResponse", "serviceFailure"):
                for e in self.events(kind, since):
                    if e.get("callId") == call_id:
                        return e
            if time.monotonic() > deadline:
                raise AssertionError(f"no answer to the call of {service} ({self._context()})")
            time.sleep(0.01)

    def parameters(self, names, request_id, timeout=10.0):
        since = self.mark()
        self.send("getParameters", names=names, id=request_id)
        answer = self.wait("parameterValues", lambda e: e.get("id") == request_id, timeout, since)
        return {p["name"]: p for p in answer["parameters"]}

    def close(self, timeout=5.0):
        if self.proc.poll() is None:
            try:
                self.send("close")
                self.proc.stdin.close()
            except (AssertionError, BrokenPipeError, OSError):
                pass
            try:
                self.proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()


# --- a raw WebSocket client ---------------------------------------------------------------------

WS_GUID = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11"
TEXT, BINARY, CLOSE = 0x1, 0x2, 0x8


class RawWebSocket:
    """A WebSocket client on a plain socket (RFC 6455, client frames masked): for what a client
    library would not send (frames that are not the protocol's, a frame too large) and for a
    reader that stops reading. Every socket operation times out."""

    def __init__(self, port, rcvbuf=None, timeout=10.0):
        self.port = port
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        if rcvbuf:
            self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)
        self.sock.settimeout(timeout)
        self.sock.connect(("127.0.0.1", port))
        self.buf = b""

    def handshake(self, subprotocol="foxglove.sdk.v1"):
        """The opening handshake; returns (HTTP status, headers with lower-case names)."""
        key = base64.b64encode(os.urandom(16)).decode()
        lines = [
            "GET / HTTP/1.1", f"Host: 127.0.0.1:{self.port}", "Upgrade: websocket",
            "Connection: Upgrade", f"Sec-WebSocket-Key: {key}", "Sec-WebSocket-Version: 13",
        ]
        if subprotocol is not None:
            lines.append(f"Sec-WebSocket-Protocol: {subprotocol}")
        self.sock.sendall(("\r\n".join(lines) + "\r\n\r\n").encode())
        while b"\r\n\r\n" not in self.buf:
            chunk = self.sock.recv(4096)
            if not chunk:
                break
            self.buf += chunk
        head, _, self.buf = self.buf.partition(b"\r\n\r\n")
        status_line, *header_lines = head.decode("latin-1").split("\r\n")
        status = int(status_line.split()[1]) if len(status_line.split()) > 1 else 0
        headers = {}
        for h in header_lines:
            name, _, value = h.partition(":")
            headers[name.strip().lower()] = value.strip()
        if status == 101:
            accept = base64.b64encode(hashlib.sha1((key + WS_GUID).encode()).digest()).decode()
            assert headers.get("sec-websocket-accept") == accept, headers
        return status, headers

    def open(self, subprotocol="foxglove.sdk.v1"):
        status, headers = self.handshake(subprotocol)
        assert status == 101, f"handshake answered {status}"
        return headers

    def send(self, opcode, payload):
        """One final frame, masked."""
        mask = os.urandom(4)
        n = len(payload)
        if n < 126:
            head = struct.pack("!BB", 0x80 | opcode, 0x80 | n)
        elif n < 1 << 16:
            head = struct.pack("!BBH", 0x80 | opcode, 0x80 | 126, n)
        else:
            head = struct.pack("!BBQ", 0x80 | opcode, 0x80 | 127, n)
        self.sock.sendall(head + mask + _masked(payload, mask))

    def send_json(self, obj):
        self.send(TEXT, json.dumps(obj).encode())

    def _read(self, n):
        while len(self.buf) < n:
            chunk = self.sock.recv(1 << 16)
            if not chunk:
                raise EOFError
            self.buf += chunk
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def recv(self):
        """The next frame from the server as (opcode, payload); EOFError when it closed."""
        b0, b1 = self._read(2)
        n = b1 & 0x7F
        if n == 126:
            (n,) = struct.unpack("!H", self._read(2))
        elif n == 127:
            (n,) = struct.unpack("!Q", self._read(8))
        return b0 & 0x0F, self._read(n)

    def recv_json(self, op):
        """The next text frame whose `op` is `op` (other frames skipped)."""
        while True:
            opcode, payload = self.recv()
            if opcode == TEXT:
                msg = json.loads(payload)
                if msg.get("op") == op:
                    return msg

    def recv_message_data(self):
        """The next binary message-data frame (opcode 0x01)."""
        while True:
            opcode, payload = self.recv()
            if opcode == BINARY and payload[:1] == b"\x01":
                return payload

    def closed_by_server(self, timeout=10.0):
        """Whether the server closes the connection (a close frame or the end of the stream)
        within `timeout`, whatever it sends before."""
        self.sock.settimeout(timeout)
        deadline = time.monotonic() + timeout
        try:
            while time.monotonic() < deadline:
                opcode, _ = self.recv()
                if opcode == CLOSE:
                    return True
        except (EOFError, ConnectionResetError, BrokenPipeError):
            return True
        except socket.timeout:
            return False
        return False

    def close(self, graceful=True):
        try:
            if graceful:
                self.send(CLOSE, struct.pack("!H", 1000))
            else:  # the peer sees a reset, as from a client that died
                self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        except OSError:
            pass
        self.sock.close()


def _masked(payload, mask):
    """`payload` XOR the repeating 4-byte mask (as big integers: fast for megabytes)."""
    n = len(payload)
    key = int.from_bytes(mask * ((n + 3) // 4), "big") >> (8 * (-n % 4))
    return (int.from_bytes(payload, "big") ^ key).to_bytes(n, "big")


def state_channel_id(ws, topic):
    """The id of channel `topic` from the server's advertise."""
    for c in ws.recv_json("advertise")["channels"]:
        if c["topic"] == topic:
            return c["id"]
    raise AssertionError(f"{topic} not advertised")


# --- ports, sockets, the node's process ---------------------------------------------------------


def free_port():
    """A TCP port free on 127.0.0.1 now (bound, then closed)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def tcp_listeners(pid):
    """The TCP sockets in LISTEN state that process `pid` holds, as sorted (address, port)."""
    inodes = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        try:
            link = os.readlink(f"/proc/{pid}/fd/{fd}")
        except OSError:
            continue
        if link.startswith("socket:["):
            inodes.add(link[len("socket:[") : -1])
    found = []
    for table in ("tcp", "tcp6"):
        path = Path(f"/proc/{pid}/net/{table}")
        if not path.exists():
            continue
        for line in path.read_text().splitlines()[1:]:
            f = line.split()
            if len(f) > 9 and f[3] == "0A" and f[9] in inodes:  # 0A: LISTEN
                addr, port = f[1].split(":")
                found.append((_proc_ip(addr), int(port, 16)))
    return sorted(found)


def start_live_node(start, namespace, *ros_args, env=None):
    """A node (started by `start`: node_factory or short_lived) with its live view on a free
    port, once the port listens; `node.port` is it."""
    port = free_port()
    node = start(namespace, "-p", f"foxglove_port:={port}", *ros_args, env=env)
    wait_until(
        lambda: not node.alive() or (("127.0.0.1", port) in tcp_listeners(node.proc.pid)), 20.0,
        what=f"the live view listening on 127.0.0.1:{port}",
    )
    assert node.alive(), node.output()
    node.port = port
    return node


def rss_mb(pid):
    for line in open(f"/proc/{pid}/status"):
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS")


def log_lines(node):
    return node.output().splitlines()


# --- recordings ---------------------------------------------------------------------------------


class RecordingTail:
    """A recording being written, read as it grows with mcap's record parsers: each complete
    top-level record once; a chunk still being written (its length a placeholder) waits for the
    next `update`. Payloads are kept for the topics in `keep` only."""

    def __init__(self, path, keep=()):
        self.path = path
        self.keep = set(keep)
        self.pos = 8  # after the magic
        self.schemas = {}  # topic -> (schema name, schema text)
        self.payloads = {t: [] for t in self.keep}
        self._schema_by_id = {}
        self._topic_by_id = {}
        self._decoders = {}

    def update(self):
        with open(self.path, "rb") as f:
            f.seek(self.pos)
            data = f.read()
        at = 0
        while at + 9 <= len(data):
            opcode, length = struct.unpack_from("<BQ", data, at)
            end = at + 9 + length
            if end > len(data):
                break
            try:
                records = self._parse(opcode, data[at + 9 : end], length)
            except Exception:  # not complete yet: read again next time
                break
            for r in records:
                self._take(r)
            at = end
        self.pos += at
        return self

    @staticmethod
    def _parse(opcode, body, length):
        stream = ReadDataStream(BytesIO(body))
        if opcode == Opcode.CHUNK:
            return breakup_chunk(Chunk.read(stream))
        if opcode == Opcode.SCHEMA:
            return [Schema.read(stream)]
        if opcode == Opcode.CHANNEL:
            return [Channel.read(stream)]
        if opcode == Opcode.MESSAGE:
            return [Message.read(stream, length)]
        return []

    def _take(self, r):
        if isinstance(r, Schema):
            self._schema_by_id[r.id] = (r.name, r.data.decode())
        elif isinstance(r, Channel):
            self._topic_by_id[r.id] = r.topic
            self.schemas[r.topic] = self._schema_by_id[r.schema_id]
        elif isinstance(r, Message):
            topic = self._topic_by_id[r.channel_id]
            if topic in self.keep:
                self.payloads[topic].append(bytes(r.data))

    def decoded(self, topic):
        """The kept messages of `topic`, decoded with mcap-ros2-support."""
        if topic not in self._decoders:
            name, text = self.schemas[topic]
            schema = Schema(id=0, name=name, encoding="ros2msg", data=text.encode())
            self._decoders[topic] = DecoderFactory().decoder_for("cdr", schema)
        return [self._decoders[topic](p) for p in self.payloads[topic]]

    def wait(self, predicate, what, timeout=15.0):
        """Reads on until `predicate(self)` holds."""
        return wait_until(lambda: predicate(self.update()), timeout, interval=0.5, what=what)


def recording_of(rec_dir):
    files = wait_until(lambda: sorted(Path(rec_dir).glob("*.mcap")), 15.0, what="the recording")
    assert len(files) == 1, files
    return files[0]


def recorded_schemas(path, topics):
    """{topic: (name, text)} of the recording, once it holds every one of `topics`."""
    tail = RecordingTail(path)
    tail.wait(lambda t: set(topics) <= set(t.schemas), f"the schemas of {sorted(topics)} in {path}")
    return tail.schemas


def sections(schema):
    """A ros2msg schema as {"": the root definition, "pkg/Name": each definition it embeds}."""
    parts = SEPARATOR.split(schema)
    out = {"": parts[0].strip("\n")}
    for part in parts[1:]:
        head, _, body = part.strip("\n").partition("\n")
        assert head.startswith("MSG: "), head
        name = head[len("MSG: ") :].strip()
        pkg, *rest = name.split("/")
        out[f"{pkg}/{rest[-1]}"] = body.strip("\n")
    return out


def code_lines(text):
    """A definition's lines without comments and blank lines."""
    return [l.split("#", 1)[0].strip() for l in text.splitlines() if l.split("#", 1)[0].strip()]


# --- comparing decoded messages -----------------------------------------------------------------


def same_bits(a, b):
    return struct.pack("<d", float(a)) == struct.pack("<d", float(b))


def assert_same(ros, fox, where="msg"):
    """An rclpy message and the Foxglove decoder's JSON of the same message: every field equal,
    doubles bit for bit."""
    if hasattr(ros, "get_fields_and_field_types"):
        assert isinstance(fox, dict), (where, fox)
        fields = list(ros.get_fields_and_field_types())
        assert sorted(fox) == sorted(fields), (where, sorted(fox), sorted(fields))
        for f in fields:
            assert_same(getattr(ros, f), fox[f], f"{where}.{f}")
    elif isinstance(ros, (list, tuple, array.array)) or type(ros).__name__ == "ndarray":
        assert isinstance(fox, list) and len(fox) == len(ros), (where, fox, list(ros))
        for k, (r, f) in enumerate(zip(ros, fox)):
            assert_same(r, f, f"{where}[{k}]")
    elif isinstance(ros, float):
        assert isinstance(fox, (int, float)) and same_bits(ros, fox), (where, ros, fox)
    elif isinstance(ros, bytes) and len(ros) == 1:  # rclpy's byte fields
        assert fox == ros[0], (where, ros, fox)
    else:
        assert ros == fox and type(ros) is type(fox), (where, ros, fox)


# --- what the rclpy peer sees -------------------------------------------------------------------


def relaxed(watch):
    """Both muscles off (over DDS), until the flexor's force is back near rest."""
    watch.activation(flexor=0.0, extensor=0.0)
    return watch.state.wait(
        lambda s: muscle(s, "flexor").force < 20.0, timeout=10.0, since=time.monotonic(),
        what="the flexor's force back below 20 N",
    )


def force_rises(watch, u, what):
    s = watch.state.wait(
        lambda s: muscle(s, "flexor").excitation == u and muscle(s, "flexor").force > 200.0,
        timeout=10.0, since=time.monotonic() - 0.5, what=what,
    )
    return muscle(s, "flexor").force


def rejections(watch, kind):
    d = watch.diagnostics()["inputs"]
    return int(d[f"rejected_{kind}"]), d.get("last_problem", "")


def rclpy_values(peer, node, names):
    client = peer.param_client(node)
    resp = peer.await_future(client.get_parameters(names))
    return {n: parameter_value_to_python(v) for n, v in zip(names, resp.values)}


def rclpy_names(peer, node):
    client = peer.param_client(node)
    return list(peer.await_future(client.list_parameters()).result.names)
