#!/usr/bin/env bash
# Creates (or brings up to date) the Python environment for the ROS 2 tests and the Python
# package, in .venv at the repository root: rclpy and the message packages of ROS 2 kilted from
# PyPI, the tools to build msg/ (muscle_actuator_msgs) for rclpy with plain cmake, pytest, the
# MCAP readers, colcon with colcon-ros-cargo (tests/python/test_colcon.py builds a colcon
# workspace), and maturin with the Python package's optional dependencies (gymnasium,
# matplotlib, pandas, ray) for scripts/test-python.sh, and OpenSim 4.6, the reference its
# OpenSim tests compare with.
#
# Idempotent: each step leaves a stamp in .venv and is skipped when its inputs did not change.
# Usage: scripts/py-env.sh            (prints the venv path on its last line)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${MUSCLE_ACTUATOR_VENV:-$ROOT/.venv}"
PY="${PYTHON:-python3}"

say() { echo "[py-env] $*" >&2; }

# Keep the list sorted; any change re-runs pip.
PACKAGES=(
  cargo-ament-build  # the cargo subcommand colcon-ros-cargo runs (a dependency of it)
  catkin-pkg
  cmake
  colcon-bash
  colcon-core
  colcon-package-information
  colcon-package-selection
  colcon-ros-cargo
  gymnasium
  matplotlib
  maturin
  mcap
  mcap-ros2-support
  mypy  # stubtest: python/muscle_actuator/_core.pyi against the built extension
  opensim==4.6  # the reference the muscles are checked against (python/tests/test_opensim_*.py)
  pandas
  pymcap-cli  # GPL: a test tool only (`doctor`), never a dependency of the product
  pytest
  pytest-timeout
  ray
  ros-kilted-ament-cmake
  ros-kilted-ament-cmake-include-directories
  ros-kilted-ament-cmake-ros-core
  ros-kilted-ament-index-python
  ros-kilted-ament-package
  ros-kilted-builtin-interfaces
  ros-kilted-diagnostic-msgs
  ros-kilted-rcl-interfaces
  ros-kilted-rclpy
  ros-kilted-rmw-fastrtps-cpp
  ros-kilted-rosgraph-msgs
  ros-kilted-rosidl-core-generators
  ros-kilted-rosidl-default-generators
  ros-kilted-rosidl-default-runtime
  ros-kilted-sensor-msgs
  ros-kilted-std-msgs
  ros-kilted-std-srvs
  rosbags
)

hash_of() { sha256sum | cut -c1-16; }

# 1. the venv
if [ ! -x "$VENV/bin/python" ]; then
  say "creating $VENV"
  "$PY" -m venv "$VENV"
fi
VPY="$VENV/bin/python"

# 2. packages
pkg_hash="$(printf '%s\n' "${PACKAGES[@]}" | hash_of)"
if [ "$(cat "$VENV/.stamp-packages" 2>/dev/null || true)" != "$pkg_hash" ]; then
  say "installing packages (pip)"
  "$VPY" -m pip install --disable-pip-version-check -q --upgrade pip >&2
  "$VPY" -m pip install --disable-pip-version-check -q "${PACKAGES[@]}" >&2
  echo "$pkg_hash" >"$VENV/.stamp-packages"
  rm -f "$VENV/.stamp-cmake-paths" "$VENV/.stamp-msgs"
fi

# 3. the wheels' exported CMake files name the manylinux build container's Python and numpy
#    include directories: point them at this venv's.
if [ ! -f "$VENV/.stamp-cmake-paths" ]; then
  say "patching CMake paths of the wheels"
  PY_INC="$("$VPY" -c 'import sysconfig; print(sysconfig.get_paths()["include"])')"
  NP_INC="$("$VPY" -c 'import numpy; print(numpy.get_include())')"
  mapfile -t files < <(grep -rlE '/opt/python/cp[0-9]+-cp[0-9]+' --include='*.cmake' "$VENV/share" "$VENV/lib" 2>/dev/null || true)
  for f in "${files[@]}"; do
    sed -i -E \
      -e "s#/opt/python/cp[0-9]+-cp[0-9]+/lib/python[0-9.]+/site-packages/numpy/_core/include#${NP_INC}#g" \
      -e "s#/opt/python/cp[0-9]+-cp[0-9]+/lib/python[0-9.]+/site-packages/numpy/core/include#${NP_INC}#g" \
      -e "s#/opt/python/cp[0-9]+-cp[0-9]+/include/python[0-9.]+#${PY_INC}#g" \
      "$f"
  done
  say "patched ${#files[@]} files"
  touch "$VENV/.stamp-cmake-paths"
fi

# 4. muscle_actuator_msgs, built with plain cmake and installed into the venv
msg_hash="$(cat "$ROOT"/msg/package.xml "$ROOT"/msg/CMakeLists.txt "$ROOT"/msg/msg/*.msg "$ROOT"/msg/srv/*.srv | hash_of)"
if [ "$(cat "$VENV/.stamp-msgs" 2>/dev/null || true)" != "$msg_hash" ] \
  || ! "$VPY" -c 'import muscle_actuator_msgs.msg' 2>/dev/null; then
  say "building muscle_actuator_msgs"
  BUILD="$ROOT/build/muscle_actuator_msgs"
  rm -rf "$BUILD"
  mkdir -p "$BUILD"
  (
    # Only the venv's tools; the bootstrap .pth of the ROS wheels sets the library paths.
    export PATH="$VENV/bin:$PATH"
    export AMENT_PREFIX_PATH="$VENV"
    export CMAKE_PREFIX_PATH="$VENV"
    export VIRTUAL_ENV="$VENV"
    cmake -S "$ROOT/msg" -B "$BUILD" \
      -DCMAKE_INSTALL_PREFIX="$VENV" \
      -DCMAKE_PREFIX_PATH="$VENV" \
      -DPython3_EXECUTABLE="$VPY" \
      -DBUILD_TESTING=OFF \
      -DCMAKE_BUILD_TYPE=Release >"$BUILD/configure.log" 2>&1 \
      || { tail -40 "$BUILD/configure.log" >&2; exit 1; }
    cmake --build "$BUILD" -j "$(nproc)" >"$BUILD/build.log" 2>&1 \
      || { tail -40 "$BUILD/build.log" >&2; exit 1; }
    cmake --install "$BUILD" >"$BUILD/install.log" 2>&1 \
      || { tail -40 "$BUILD/install.log" >&2; exit 1; }
  )
  "$VPY" -c 'from muscle_actuator_msgs.msg import ActuatorState, ActivationCommand, ExternalLoad, MuscleState' \
    || { say "muscle_actuator_msgs built but not importable"; exit 1; }
  echo "$msg_hash" >"$VENV/.stamp-msgs"
fi

say "ready: $VENV"
echo "$VENV"
