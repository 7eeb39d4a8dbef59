# The environment shared by the scripts that run the node against an rclpy peer on this host only
# (scripts/test-ros.sh, scripts/bench-flood.sh, benches/rclpy-bench.sh, launch-scripts/demo.sh).
# Sourced, not run:   source "$(dirname "${BASH_SOURCE[0]}")/../scripts/lib.sh"
#
#   ROOT                  the repository
#   target_dir            prints the cargo target directory, absolute ($CARGO_TARGET_DIR, relative
#                         to ROOT as cargo reads it, or ROOT/target)
#   python_env            prints the Python environment, created or brought up to date
#                         (scripts/py-env.sh)
#   loopback_env          exports loopback-only discovery (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST,
#                         no ROS_LOCALHOST_ONLY), a domain of its own (ROS_DOMAIN_ID from
#                         $MUSCLE_ACTUATOR_TEST_DOMAIN, else 120 + PID % 80) and
#                         PYTHONDONTWRITEBYTECODE=1
#   netns_available       true when a fresh network namespace can be had (`unshare -n` works,
#                         `ip` exists) and MUSCLE_ACTUATOR_NO_NETNS is not 1
#   exec_on_loopback TAG CMD...
#                         replaces the shell with CMD inside a fresh network namespace with only
#                         loopback up when netns_available, else with CMD as it is (discovery
#                         then kept to this host by loopback_env); says which on stderr as [TAG]

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

target_dir() {
  local dir="${CARGO_TARGET_DIR:-$ROOT/target}"
  case "$dir" in /*) ;; *) dir="$ROOT/$dir" ;; esac
  echo "$dir"
}

python_env() {
  "$ROOT/scripts/py-env.sh" | tail -n 1
}

loopback_env() {
  export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
  unset ROS_LOCALHOST_ONLY
  export ROS_DOMAIN_ID="${MUSCLE_ACTUATOR_TEST_DOMAIN:-$((120 + $$ % 80))}"
  export PYTHONDONTWRITEBYTECODE=1
}

netns_available() {
  [ "${MUSCLE_ACTUATOR_NO_NETNS:-}" != 1 ] && command -v unshare >/dev/null && command -v ip >/dev/null \
    && unshare -n true 2>/dev/null
}

exec_on_loopback() {
  local tag="$1"
  shift
  if netns_available; then
    echo "[$tag] running in a loopback-only network namespace (domain ${ROS_DOMAIN_ID:-0})" >&2
    exec unshare -n bash -c 'ip link set lo up && exec "$@"' bash "$@"
  fi
  echo "[$tag] no network namespace here: loopback-only discovery (domain ${ROS_DOMAIN_ID:-0})" >&2
  exec "$@"
}
