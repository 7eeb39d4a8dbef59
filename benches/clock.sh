#!/usr/bin/env bash
# Simulated-time benchmark: benches/clock.sh [--release] [--duration S] [--steps N] [--best-effort]
# (benches/clock_bench.py through benches/rclpy-bench.sh: build, venv, loopback only).
exec "$(dirname "${BASH_SOURCE[0]}")/rclpy-bench.sh" clock_bench.py "$@"
