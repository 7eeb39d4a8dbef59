// ROS 2 message definitions (`ros2msg` text) for the messages this client publishes: the
// repository's own (msg/msg/*.msg, read from the checkout) and the standard ones the node's
// inputs use, written here. `schemaText` joins a type's definition with those of every type it
// uses, in the format of MCAP's ros2msg schemas and of Foxglove's WebSocket channels; `writerFor`
// and `readerFor` build the Foxglove app's own CDR codec on such a text.

import { readdirSync, readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

import { parse } from "@foxglove/rosmsg";
import { MessageReader, MessageWriter } from "@foxglove/rosmsg2-serialization";

const REPO_MSG_DIR = join(dirname(fileURLToPath(import.meta.url)), "..", "..", "msg", "msg");
const REPO_PACKAGE = "muscle_actuator_msgs";

// The standard definitions, as in ROS 2 (kilted) without their comments.
const STANDARD = {
  "builtin_interfaces/Time": "int32 sec\nuint32 nanosec\n",
  "std_msgs/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
  "std_msgs/Float64": "float64 data\n",
  "std_msgs/Float64MultiArray": "MultiArrayLayout layout\nfloat64[] data\n",
  "std_msgs/MultiArrayLayout": "MultiArrayDimension[] dim\nuint32 data_offset\n",
  "std_msgs/MultiArrayDimension": "string label\nuint32 size\nuint32 stride\n",
};

const PRIMITIVES = new Set([
  "bool", "byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64",
  "uint64", "float32", "float64", "string", "wstring", "time", "duration",
]);

const SEPARATOR = "=".repeat(80);

/** `pkg/msg/Name` or `pkg/Name` as `pkg/Name`. */
export function shortName(type) {
  const parts = type.split("/");
  return parts.length === 3 ? `${parts[0]}/${parts[2]}` : type;
}

function repoDefinitions() {
  const out = {};
  for (const file of readdirSync(REPO_MSG_DIR)) {
    if (file.endsWith(".msg")) {
      out[`${REPO_PACKAGE}/${file.slice(0, -4)}`] = readFileSync(join(REPO_MSG_DIR, file), "utf8");
    }
  }
  return out;
}

const DEFINITIONS = { ...STANDARD, ...repoDefinitions() };

/** Whether this client has a definition for `type` (`pkg/msg/Name` or `pkg/Name`). */
export function knows(type) {
  return shortName(type) in DEFINITIONS;
}

/** The message types a definition's fields use, as `pkg/Name` (constants and primitives not). */
function fieldTypes(text, pkg) {
  const types = [];
  for (const line of text.split("\n")) {
    const code = line.replace(/#.*/, "").trim();
    if (!code || code.includes("=")) {
      continue; // a comment, a blank line or a constant
    }
    const base = code.split(/\s+/)[0].replace(/\[.*\]$/, "").replace(/<=.*$/, "");
    if (PRIMITIVES.has(base)) {
      continue;
    }
    types.push(base.includes("/") ? shortName(base) : `${pkg}/${base}`);
  }
  return types;
}

/** The full ros2msg text of `type`: its definition, then each type it uses once, depth first. */
export function schemaText(type) {
  const root = shortName(type);
  const seen = new Set([root]);
  const parts = [definitionOf(root)];
  const visit = (name) => {
    for (const dep of fieldTypes(definitionOf(name), name.split("/")[0])) {
      if (!seen.has(dep)) {
        seen.add(dep);
        parts.push(`${SEPARATOR}\nMSG: ${dep}\n${definitionOf(dep)}`);
        visit(dep);
      }
    }
  };
  visit(root);
  return parts.join("\n");
}

function definitionOf(name) {
  const text = DEFINITIONS[name];
  if (text === undefined) {
    throw new Error(`no message definition for ${name}`);
  }
  return text.endsWith("\n") ? text : text + "\n";
}

/** The Foxglove app's CDR writer for a schema text (ros2msg). */
export function writerFor(text) {
  return new MessageWriter(parse(text, { ros2: true }));
}

/** The Foxglove app's CDR reader for a schema text (ros2msg). */
export function readerFor(text) {
  return new MessageReader(parse(text, { ros2: true }));
}
