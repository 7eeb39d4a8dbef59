#!/usr/bin/env node
// A line-driven Foxglove WebSocket client for the tests (tests/python/test_foxglove.py): the
// Foxglove app's own protocol client (@foxglove/ws-protocol) and CDR codec
// (@foxglove/rosmsg2-serialization on schemas parsed by @foxglove/rosmsg), so that what it
// decodes is what the app would show.
//
//   node client.mjs --url ws://127.0.0.1:PORT [--subprotocol foxglove.sdk.v1]
//
// stdin: one JSON command per line.
//   {"cmd":"subscribe","topic":T,"max":N,"raw":B} print the first N decoded messages of T (all
//                                                 when max is absent; with raw, their payload
//                                                 as "hex" too), then count silently
//   {"cmd":"count","topic":T}                     -> {"event":"count","topic":T,"n":K}
//   {"cmd":"unsubscribe","topic":T}
//   {"cmd":"advertise","topic":T,"encoding":"cdr"|"json","schemaName":S}
//                                                 -> {"event":"advertised","topic":T,"id":K}
//   {"cmd":"publish","topic":T,"message":{...}}   CDR from the definitions in schemas.mjs, or
//                                                 UTF-8 JSON -> {"event":"published",...}
//   {"cmd":"getParameters","names":[...],"id":X}
//   {"cmd":"setParameters","parameters":[{"name":..,"value":..,"type"?:..}],"id":X}
//   {"cmd":"callService","service":NAME,"request":{...},"encoding":"cdr"}
//                                                 -> {"event":"called","service":..,"callId":K}
//   {"cmd":"close"}                               close; the process exits after "close"
// stdout: one JSON event per line (jsonl.mjs: 64-bit integers exact, typed arrays as arrays):
//   open, serverInfo, advertise, unadvertise, advertiseServices, message, time, status,
//   removeStatus, parameterValues, serviceResponse, serviceFailure, close, error, and the
//   acknowledgements above. A command that cannot be carried out is an "error" event naming it;
//   the client goes on. End of stdin closes the connection.

import { createInterface } from "node:readline";
import { parseArgs } from "node:util";

import wsProtocol from "@foxglove/ws-protocol"; // CommonJS: its exports through the default
import WebSocket from "ws";

import { emit } from "./jsonl.mjs";
import { knows, readerFor, schemaText, writerFor } from "./schemas.mjs";

const { values: args } = parseArgs({
  options: {
    url: { type: "string" },
    subprotocol: { type: "string", default: "foxglove.sdk.v1" },
  },
});
if (!args.url) {
  console.error("usage: client.mjs --url ws://127.0.0.1:PORT [--subprotocol NAME]");
  process.exit(2);
}

const { FoxgloveClient } = wsProtocol;
const textEncoder = new TextEncoder();
const textDecoder = new TextDecoder();

// What the server offered, by topic / name.
const channels = new Map(); // topic -> {channel, reader}
const services = new Map(); // name -> {service, writer, reader}
// What this client asked for.
const subscriptions = new Map(); // topic -> {id, max, raw, n}; id undefined until advertised
const bySubscriptionId = new Map(); // subscription id -> topic
const published = new Map(); // topic -> {id, encoding, schemaName, writer}
const calls = new Map(); // call id -> service name
let nextCallId = 1;
// Commands read before the connection is open wait for it.
const pending = [];
let stdinClosed = false;

const ws = new WebSocket(args.url, [args.subprotocol]);
const client = new FoxgloveClient({ ws });

// --- server events ------------------------------------------------------------------------

client.on("open", () => {
  emit({ event: "open", protocol: ws.protocol });
  for (const line of pending.splice(0)) {
    run(line);
  }
  if (stdinClosed) {
    client.close();
  }
});
client.on("error", (e) => emit({ event: "error", message: String(e?.message ?? e) }));
client.on("close", (e) => {
  emit({ event: "close", code: e.code, reason: String(e.reason ?? "") });
  process.exit(0);
});
// A handshake refused (HTTP 400, ...): `ws` reports it here, before any open.
ws.on("unexpected-response", (_req, res) => {
  emit({ event: "error", message: `unexpected response ${res.statusCode}`, status: res.statusCode });
  process.exit(0);
});

client.on("serverInfo", (info) => emit({ event: "serverInfo", ...info }));
client.on("status", (s) => emit({ event: "status", ...s }));
client.on("removeStatus", (s) => emit({ event: "removeStatus", ...s }));
client.on("time", (t) => emit({ event: "time", ns: t.timestamp }));
client.on("parameterValues", (p) => emit({ event: "parameterValues", ...p }));
client.on("serviceCallFailure", (f) => emit({ event: "serviceFailure", ...f }));

client.on("advertise", (list) => {
  for (const channel of list) {
    channels.set(channel.topic, { channel, reader: channelReader(channel) });
    const sub = subscriptions.get(channel.topic);
    if (sub && sub.id === undefined) {
      subscribeNow(channel.topic, sub);
    }
  }
  emit({ event: "advertise", channels: list });
});

client.on("unadvertise", (ids) => {
  for (const [topic, { channel }] of channels) {
    if (ids.includes(channel.id)) {
      channels.delete(topic);
    }
  }
  emit({ event: "unadvertise", channelIds: ids });
});

client.on("advertiseServices", (list) => {
  for (const service of list) {
    services.set(service.name, serviceCodec(service));
  }
  emit({ event: "advertiseServices", services: list });
});

client.on("message", (m) => {
  const topic = bySubscriptionId.get(m.subscriptionId);
  const sub = topic === undefined ? undefined : subscriptions.get(topic);
  if (!sub) {
    return; // unsubscribed meanwhile
  }
  sub.n += 1;
  if (sub.max === undefined || sub.n <= sub.max) {
    const { reader } = channels.get(topic) ?? {};
    const event = { event: "message", topic, receiveTimeNs: m.timestamp, data: decode(reader, m.data) };
    if (sub.raw) {
      event.hex = Buffer.from(m.data.buffer, m.data.byteOffset, m.data.byteLength).toString("hex");
    }
    emit(event);
  }
});

client.on("serviceCallResponse", (r) => {
  const name = calls.get(r.callId);
  calls.delete(r.callId);
  const codec = services.get(name);
  emit({
    event: "serviceResponse",
    service: name,
    callId: r.callId,
    encoding: r.encoding,
    data: decode(codec?.reader, r.data),
  });
});

// --- decoding ------------------------------------------------------------------------------

/** The CDR reader of a cdr/ros2msg channel, or undefined (its payloads are then shown raw). */
function channelReader(channel) {
  if (channel.encoding !== "cdr" || channel.schemaEncoding !== "ros2msg") {
    return undefined;
  }
  try {
    return readerFor(channel.schema);
  } catch (e) {
    emit({ event: "error", message: `schema of ${channel.topic}: ${e.message}` });
    return undefined;
  }
}

/** A service's request writer and response reader, from its advertised ros2msg schemas. */
function serviceCodec(service) {
  const request = service.request?.schema ?? service.requestSchema;
  const response = service.response?.schema ?? service.responseSchema;
  const codec = { service, writer: undefined, reader: undefined };
  try {
    codec.writer = request === undefined ? undefined : writerFor(request);
    codec.reader = response === undefined ? undefined : readerFor(response);
  } catch (e) {
    emit({ event: "error", message: `schemas of service ${service.name}: ${e.message}` });
  }
  return codec;
}

/** A payload decoded with `reader`; without one, JSON text parsed, else its bytes. */
function decode(reader, view) {
  const bytes = new Uint8Array(view.buffer, view.byteOffset, view.byteLength);
  if (reader) {
    try {
      return reader.readMessage(bytes);
    } catch (e) {
      return { decodeError: e.message, bytes: Array.from(bytes) };
    }
  }
  try {
    return JSON.parse(textDecoder.decode(bytes));
  } catch {
    return { bytes: Array.from(bytes) };
  }
}

// --- commands ------------------------------------------------------------------------------

function subscribeNow(topic, sub) {
  sub.id = client.subscribe(channels.get(topic).channel.id);
  bySubscriptionId.set(sub.id, topic);
}

const COMMANDS = {
  subscribe({ topic, max, raw }) {
    const sub = { id: undefined, max: max ?? undefined, raw: Boolean(raw), n: 0 };
    subscriptions.set(topic, sub);
    // A channel not advertised yet is subscribed to when it is.
    if (channels.has(topic)) {
      subscribeNow(topic, sub);
    }
  },

  count({ topic }) {
    emit({ event: "count", topic, n: subscriptions.get(topic)?.n ?? 0 });
  },

  unsubscribe({ topic }) {
    const sub = subscriptions.get(topic);
    subscriptions.delete(topic);
    if (sub?.id !== undefined) {
      bySubscriptionId.delete(sub.id);
      client.unsubscribe(sub.id);
    }
  },

  advertise({ topic, encoding, schemaName }) {
    const channel = { topic, encoding, schemaName };
    let writer;
    // A type this client knows is advertised with its schema, as the Foxglove app does.
    if (encoding === "cdr" && knows(schemaName)) {
      channel.schemaEncoding = "ros2msg";
      channel.schema = schemaText(schemaName);
      writer = writerFor(channel.schema);
    }
    const id = client.advertise(channel);
    published.set(topic, { id, encoding, schemaName, writer });
    emit({ event: "advertised", topic, id });
  },

  publish({ topic, message }) {
    const p = published.get(topic);
    if (!p) {
      throw new Error(`${topic} is not advertised by this client`);
    }
    let data;
    if (p.encoding === "json") {
      data = textEncoder.encode(JSON.stringify(message));
    } else if (p.writer) {
      data = p.writer.writeMessage(message);
    } else {
      throw new Error(`no CDR definition for ${p.schemaName}`);
    }
    client.sendMessage(p.id, data);
    emit({ event: "published", topic, bytes: data.byteLength });
  },

  getParameters({ names, id }) {
    client.getParameters(names ?? [], id);
  },

  setParameters({ parameters, id }) {
    client.setParameters(parameters, id);
  },

  callService({ service, request, encoding }) {
    const codec = services.get(service);
    if (!codec) {
      throw new Error(`no service ${service} advertised`);
    }
    const enc = encoding ?? "cdr";
    let data;
    if (enc === "json") {
      data = textEncoder.encode(JSON.stringify(request ?? {}));
    } else if (codec.writer) {
      data = codec.writer.writeMessage(request ?? {});
    } else {
      throw new Error(`no request schema for ${service}`);
    }
    const callId = nextCallId++;
    calls.set(callId, service);
    client.sendServiceCallRequest({ serviceId: codec.service.id, callId, encoding: enc, data });
    emit({ event: "called", service, callId });
  },

  close() {
    client.close();
  },
};

function run(line) {
  if (!line.trim()) {
    return;
  }
  if (ws.readyState === WebSocket.CONNECTING) {
    pending.push(line);
    return;
  }
  let command;
  try {
    command = JSON.parse(line);
    const handler = COMMANDS[command.cmd];
    if (!handler) {
      throw new Error("unknown command");
    }
    handler(command);
  } catch (e) {
    emit({ event: "error", message: `${command?.cmd ?? "command"}: ${e.message}`, line });
  }
}

const input = createInterface({ input: process.stdin });
input.on("line", run);
// No more commands: close once the commands read are sent (the close event ends the process).
input.on("close", () => {
  stdinClosed = true;
  if (ws.readyState === WebSocket.OPEN) {
    client.close();
  } else if (ws.readyState === WebSocket.CLOSED) {
    process.exit(0);
  } // CONNECTING: closed once open; CLOSING: the close event follows
});
