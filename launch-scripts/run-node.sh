#!/usr/bin/env bash
# Starts the node with a common configuration.
#
#   launch-scripts/run-node.sh [--ns /NS] [--name NAME] [--model NAME]
#                              [--rate HZ] [--publish-rate HZ] [--config arm|FILE.toml]
#                              [--domain ID] [--subnet] [-- more ROS arguments]
#
# The models are those `muscle_actuator models` lists (the node's default without --model).
# Discovery stays on this host unless --subnet is given. The binary is $MUSCLE_ACTUATOR_BIN, or
# the newer of target/release and target/debug under $CARGO_TARGET_DIR or target/ (built with
# `cargo build` if neither exists).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

ns=/ name="" model="" rate="" prate="" config="" extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --ns) ns="$2"; shift 2 ;;
    --name) name="$2"; shift 2 ;;
    --model) model="$2"; shift 2 ;;
    --rate) rate="$2"; shift 2 ;;
    --publish-rate) prate="$2"; shift 2 ;;
    --config) config="$2"; shift 2 ;;
    --domain) export ROS_DOMAIN_ID="$2"; shift 2 ;;
    --subnet) export ROS_AUTOMATIC_DISCOVERY_RANGE=SUBNET; shift ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "run-node.sh: unknown option $1 (try --help)" >&2; exit 2 ;;
  esac
done
export ROS_AUTOMATIC_DISCOVERY_RANGE="${ROS_AUTOMATIC_DISCOVERY_RANGE:-LOCALHOST}"

bin="${MUSCLE_ACTUATOR_BIN:-}"
if [ -z "$bin" ]; then
  # The newer of the release and debug builds (in CARGO_TARGET_DIR when set).
  target="${CARGO_TARGET_DIR:-$ROOT/target}"
  case "$target" in /*) ;; *) target="$ROOT/$target" ;; esac
  for b in "$target/release/muscle_actuator" "$target/debug/muscle_actuator"; do
    if [ -x "$b" ] && { [ -z "$bin" ] || [ "$b" -nt "$bin" ]; }; then bin="$b"; fi
  done
fi
if [ -z "$bin" ]; then
  (cd "$ROOT" && cargo build --quiet --bin muscle_actuator)
  bin="$target/debug/muscle_actuator"
fi

args=(--ros-args -r "__ns:=$ns")
[ -n "$name" ] && args+=(-r "__node:=$name")
[ -n "$model" ] && args+=(-p "model:=$model")
# Doubles: ROS parameters are typed, `1000` would be an integer.
dbl() { case "$1" in *.*|*e*|*E*) echo "$1" ;; *) echo "$1.0" ;; esac; }
[ -n "$rate" ] && args+=(-p "rate_hz:=$(dbl "$rate")")
[ -n "$prate" ] && args+=(-p "publish_rate_hz:=$(dbl "$prate")")
[ -n "$config" ] && args+=(-p "config:=$config")
exec "$bin" node "${args[@]}" "${extra[@]}"
