#!/usr/bin/env bash
# Every test of the project, on a fresh machine or an old one (idempotent, reuses what is built):
#   0. lint: rustfmt's check and clippy with every warning an error, on every crate and target,
#      and the engine's, measured-data and recording crates' documentation built without a
#      warning;
#   1. the Rust tests of every crate of the workspace (crates/core, crates/measured,
#      crates/recording, the node's and the CLI's): unit, integration (physics against closed forms, the adaptive reference
#      solver, conservation laws; the CLI), and the benchmarks compiled and run once in test mode;
#      then the fourth model's tests (the `test-model` feature) and the test topic's (the
#      `test-topic` feature: a whole node with a DDS peer and a live-view client, in a
#      loopback-only network namespace);
#   2. the structure checks of every crate's sources (scripts/check-structure.py: file sizes,
#      function lengths, import cycles);
#   3. the ROS 2 tests: a real rclpy peer (ROS 2 kilted from PyPI, Fast DDS) against the node, in
#      a loopback-only network namespace (scripts/test-ros.sh; it creates .venv and builds the
#      message package for rclpy on first use);
#   4. the Python package: its wheel built and installed into .venv, and its tests (parity with
#      the command line, batched rollouts, pickles across processes, recordings, Gymnasium, a
#      sweep on Ray) in a loopback-only network namespace (scripts/test-python.sh);
#   5. the demo of docs/testing.md, which must end cleanly.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
echo "== Lint: cargo fmt --check, cargo clippy -D warnings (every crate, every target)" >&2
cargo fmt --all --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
cargo clippy --lib --tests --quiet --features test-model,test-topic -- -D warnings
# The engine's, the measured-data and the recording crates' API documentation, every link
# resolved (their missing_docs lint, part of clippy above, asks for a doc on every public item).
RUSTDOCFLAGS="-D warnings" cargo doc --quiet --no-deps -p muscle_actuator_core -p muscle_actuator_measured \
    -p muscle_actuator_recording
echo "== Rust tests" >&2
cargo test --workspace --exclude muscle_actuator_python --all-targets
echo "== The fourth model and the test topic (a model and a topic only the tests know)" >&2
cargo test --features test-model,test-topic --lib -q fourth
(source scripts/lib.sh && loopback_env && exec_on_loopback test-topic \
    cargo test --offline --features test-model,test-topic --lib -q -- --ignored one_place_topic)
echo "== Structure checks (scripts/check-structure.py)" >&2
python3 scripts/check-structure.py
python3 scripts/check-structure.py --src crates/core/src --crate-name muscle_actuator_core
python3 scripts/check-structure.py --src crates/measured/src --crate-name muscle_actuator_measured
python3 scripts/check-structure.py --src crates/recording/src --crate-name muscle_actuator_recording
python3 scripts/check-structure.py --src python/src --crate-name _core
echo "== ROS 2 tests (rclpy peer)" >&2
MUSCLE_ACTUATOR_BUILT=1 bash scripts/test-ros.sh -q
echo "== Python package (scripts/test-python.sh)" >&2
MUSCLE_ACTUATOR_BUILT=1 bash scripts/test-python.sh -q
echo "== Demo (launch-scripts/demo.sh: the node and an rclpy co-contraction sweep)" >&2
bash launch-scripts/demo.sh
