#!/usr/bin/env bash
# Simulated-time benchmark: benches/clock.sh [--release] [--duration S] [--steps N] [--best-effort]
# (benches/clock_bench.py through benches/py-bench.sh: build, venv, loopback only).
exec "$(dirname "${BASH_SOURCE[0]}")/py-bench.sh" clock_bench.py "$@"
