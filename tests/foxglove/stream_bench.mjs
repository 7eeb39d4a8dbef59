#!/usr/bin/env node
// The live view's stream as a Foxglove user sees it, for benches/node_rate.py --foxglove on:
// subscribes to every channel the node advertises, decodes each message with the Foxglove
// app's CDR decoder, and measures for `~/state` the latency from the tick's stamp (wall clock,
// ns since the Unix epoch) to its arrival here. On SIGTERM (or the end of stdin) prints one
// JSON line: messages per topic, and the latency's p50, p99 and max in ms.
//
//   node stream_bench.mjs --url ws://127.0.0.1:PORT --state /bench/muscle_actuator/state

import { parseArgs } from "node:util";

import wsProtocol from "@foxglove/ws-protocol";
import { parse as parseMsg } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import WebSocket from "ws";

const { values: args } = parseArgs({
  options: { url: { type: "string" }, state: { type: "string" } },
});
const { FoxgloveClient } = wsProtocol;
const client = new FoxgloveClient({
  ws: new WebSocket(args.url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]),
});

const readers = new Map(); // subscription id -> {topic, reader}
const counts = {};
const latencies = []; // ms
const nowNs = () => BigInt(Math.round((performance.timeOrigin + performance.now()) * 1e6));

client.on("advertise", (channels) => {
  for (const ch of channels) {
    const reader = new MessageReader(parseMsg(ch.schema, { ros2: true }));
    const id = client.subscribe(ch.id);
    readers.set(id, { topic: ch.topic, reader });
    counts[ch.topic] = 0;
  }
});

client.on("message", ({ subscriptionId, timestamp, data }) => {
  const arrived = nowNs();
  const r = readers.get(subscriptionId);
  if (!r) return;
  const msg = r.reader.readMessage(data);
  counts[r.topic] += 1;
  if (r.topic === args.state) {
    const stamp = BigInt(msg.header.stamp.sec) * 1000000000n + BigInt(msg.header.stamp.nanosec);
    latencies.push(Number(arrived - stamp) / 1e6);
  }
  void timestamp;
});

function pct(xs, q) {
  if (xs.length === 0) return null;
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.max(0, Math.round(q * (s.length - 1))))];
}

function report() {
  console.log(
    JSON.stringify({
      counts,
      state_latency_ms: {
        n: latencies.length,
        p50: pct(latencies, 0.5),
        p99: pct(latencies, 0.99),
        max: latencies.length ? latencies.reduce((a, b) => Math.max(a, b)) : null,
      },
    }),
  );
  process.exit(0);
}

process.on("SIGTERM", report);
process.stdin.on("end", report);
process.stdin.resume();
