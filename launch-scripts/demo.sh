#!/usr/bin/env bash
# Demo: starts the node and runs the co-contraction sweep against it, on this host only
# (inside a loopback-only network namespace when run as root).
#
#   launch-scripts/demo.sh [--model NAME] [--rate HZ]      (models: `muscle_actuator models`)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
model="" rate=1000  # no --model: the node's default model
while [ $# -gt 0 ]; do
  case "$1" in
    --model) model="$2"; shift 2 ;;
    --rate) rate="$2"; shift 2 ;;
    -h|--help) sed -n '2,5p' "$0"; exit 0 ;;
    *) echo "demo.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
source "$ROOT/scripts/lib.sh"
if [ -z "${MUSCLE_ACTUATOR_DEMO_INNER:-}" ] && netns_available; then
  export MUSCLE_ACTUATOR_DEMO_INNER=1
  exec unshare -n bash -c 'ip link set lo up && exec "$@"' bash "$0" --model "$model" --rate "$rate"
fi
VENV="$(python_env)"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
export ROS_DOMAIN_ID="${ROS_DOMAIN_ID:-42}"
"$ROOT/launch-scripts/run-node.sh" --ns /demo --model "$model" --rate "$rate" --publish-rate 100 \
  -- --log-level warn &
node_pid=$!
trap 'kill -INT $node_pid 2>/dev/null; wait $node_pid 2>/dev/null || true' EXIT
"$VENV/bin/python" "$ROOT/launch-scripts/cocontraction_sweep.py" --node /demo/muscle_actuator
