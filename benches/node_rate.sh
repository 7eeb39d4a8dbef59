#!/usr/bin/env bash
# Node-rate benchmark: benches/node_rate.sh [--release] [--duration S] [--model M] [--json FILE]
# (benches/node_rate.py through benches/rclpy-bench.sh: build, venv, loopback only).
exec "$(dirname "${BASH_SOURCE[0]}")/rclpy-bench.sh" node_rate.py "$@"
