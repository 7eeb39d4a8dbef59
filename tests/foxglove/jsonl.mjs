// One JSON object per line on stdout, for a reader in another language (the pytest).
//
// Values the Foxglove decoder produces that JSON.stringify would lose are written as JSON that
// Python's json module reads exactly:
//   - BigInt (uint64/int64 fields, timestamps): the integer's decimal digits, unquoted, never
//     rounded to a double;
//   - NaN, Infinity, -Infinity: the bare tokens Python's json accepts; -0 as -0.0 (not 0);
//   - typed arrays (float64[], uint8[], ...): plain arrays.

// Private-use characters around a raw token: JSON.stringify leaves them as they are, and no
// message of the node carries them.
const OPEN = "\uE000";
const CLOSE = "\uE001";
const MARKED = new RegExp(`"${OPEN}([^"${CLOSE}]*)${CLOSE}"`, "g");

function replacer(_key, value) {
  if (typeof value === "bigint") {
    return OPEN + value.toString() + CLOSE;
  }
  if (typeof value === "number" && !Number.isFinite(value)) {
    return OPEN + (Number.isNaN(value) ? "NaN" : value > 0 ? "Infinity" : "-Infinity") + CLOSE;
  }
  if (Object.is(value, -0)) {
    return OPEN + "-0.0" + CLOSE;
  }
  if (ArrayBuffer.isView(value) && !(value instanceof DataView)) {
    return Array.from(value);
  }
  return value;
}

/** `value` as one line of JSON, with the rules above. */
export function toJsonLine(value) {
  return JSON.stringify(value, replacer).replace(MARKED, "$1");
}

/** Writes `value` as one line on stdout. */
export function emit(value) {
  process.stdout.write(toJsonLine(value) + "\n");
}
