"""`colcon build` of a workspace holding this repository and msg/, as a ROS 2 user builds it.

The workspace is a temporary directory: src/muscle_actuator -> the repository, and
src/muscle_actuator_msgs -> msg/ (colcon does not look for packages inside a package). colcon
(colcon-ros-cargo, cargo-ament-build, from .venv) builds muscle_actuator_msgs with ament_cmake on
the ROS 2 packages of .venv, and muscle_actuator with cargo. The cargo build reuses the
already-built node: cargo-ament-build builds with `--target-dir build/muscle_actuator`, whose
profile directory (debug) is made a link to the one of the node under test
($MUSCLE_ACTUATOR_BIN), so cargo finds everything fresh instead of compiling the crate and its
dependencies again.

Checks: the build succeeds; lib/muscle_actuator/node, the executable `ros2 run muscle_actuator
node` runs (found the way ros2run finds it), answers --help as `muscle_actuator node` does; with
install/setup.bash sourced, ament_index_python finds the package's prefix and the ament index
holds its resource file; the messages built by colcon import and serialize from the install.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VENV = Path(sys.prefix)  # the test runs on .venv's Python (scripts/test-ros.sh)

# colcon builds muscle_actuator_msgs from scratch (about half a minute): one build per module.
pytestmark = pytest.mark.timeout(900)


def node_binary():
    b = os.environ.get("MUSCLE_ACTUATOR_BIN")
    return Path(b) if b else ROOT / "target" / "debug" / "muscle_actuator"


def colcon_env(ws):
    """The environment of a user with ROS 2 (here: .venv's packages from PyPI) as the underlay."""
    env = dict(os.environ)
    env["PATH"] = f"{VENV / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["AMENT_PREFIX_PATH"] = str(VENV)
    env["CMAKE_PREFIX_PATH"] = str(VENV)
    env["COLCON_HOME"] = str(ws / ".colcon")  # no user defaults
    env["CARGO_NET_OFFLINE"] = "true"  # everything is fetched: fail at once rather than wait
    for k in ("COLCON_PREFIX_PATH", "CARGO_TARGET_DIR", "PYTHONPATH"):
        env.pop(k, None)
    return env


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    ws = tmp_path_factory.mktemp("colcon_ws")
    (ws / "src").mkdir()
    (ws / "src" / "muscle_actuator").symlink_to(ROOT)
    (ws / "src" / "muscle_actuator_msgs").symlink_to(ROOT / "msg")

    # Both packages are found, each with its build type (without package.xml the repository
    # would be a plain cargo package, built and installed another way).
    r = subprocess.run([str(VENV / "bin" / "colcon"), "list"], cwd=ws, env=colcon_env(ws),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=60)
    assert r.returncode == 0, r.stdout
    assert sorted(r.stdout.splitlines()) == [
        "muscle_actuator\tsrc/muscle_actuator\t(ament_cargo)",
        "muscle_actuator_msgs\tsrc/muscle_actuator_msgs\t(ros.ament_cmake)",
    ], r.stdout

    cmd = [
        str(VENV / "bin" / "colcon"), "build",
        "--cmake-args", "-DBUILD_TESTING=OFF", f"-DPython3_EXECUTABLE={VENV / 'bin' / 'python'}",
    ]
    # Reuse the node's build: its profile directory becomes the one cargo-ament-build uses.
    profile_dir = node_binary().parent
    if profile_dir.name in ("debug", "release") and profile_dir.is_dir():
        (ws / "build" / "muscle_actuator").mkdir(parents=True)
        (ws / "build" / "muscle_actuator" / profile_dir.name).symlink_to(profile_dir)
        if profile_dir.name == "release":
            cmd += ["--cargo-args", "--release"]

    r = subprocess.run(cmd, cwd=ws, env=colcon_env(ws), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=840)
    assert r.returncode == 0, f"colcon build failed:\n{r.stdout[-6000:]}"
    assert "Finished <<< muscle_actuator_msgs" in r.stdout, r.stdout[-3000:]
    assert "Finished <<< muscle_actuator " in r.stdout, r.stdout[-3000:]
    yield ws
    # about 200 MB (the debug binary): not left behind for pytest's last three runs.
    # rmtree unlinks the links to the repository and the target directory without following them.
    shutil.rmtree(ws, ignore_errors=True)


@pytest.fixture(scope="module")
def sourced_env(workspace):
    """The environment after `source install/setup.bash`, as a user has it."""
    out = subprocess.run(
        ["bash", "-c", 'source install/setup.bash && env -0'], cwd=workspace,
        env=colcon_env(workspace), stdout=subprocess.PIPE, check=True,
    ).stdout
    env = dict(kv.split("=", 1) for kv in out.decode().split("\0") if "=" in kv)
    assert str(workspace / "install" / "muscle_actuator") in env["AMENT_PREFIX_PATH"].split(os.pathsep)
    return env


def run_python(env, code):
    r = subprocess.run([str(VENV / "bin" / "python"), "-c", code], env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    return r.stdout.strip()


def test_ament_index_finds_the_package(workspace, sourced_env):
    prefix = workspace / "install" / "muscle_actuator"
    got = run_python(sourced_env, "from ament_index_python.packages import get_package_prefix; "
                                  "print(get_package_prefix('muscle_actuator'))")
    assert Path(got) == prefix
    assert (prefix / "share" / "ament_index" / "resource_index" / "packages" / "muscle_actuator").is_file()
    assert (prefix / "share" / "muscle_actuator" / "package.xml").is_file()
    # and the message package beside it
    got = run_python(sourced_env, "from ament_index_python.packages import get_package_prefix; "
                                  "print(get_package_prefix('muscle_actuator_msgs'))")
    assert Path(got) == workspace / "install" / "muscle_actuator_msgs"


def ros2_run_executable(env, package, executable):
    """What `ros2 run PACKAGE EXECUTABLE` runs: ros2run.api.get_executable_path (ros2cli is not on
    PyPI): an executable file of that name under <prefix>/lib/<package>/."""
    code = f"""
import os
from ament_index_python.packages import get_package_prefix
base = os.path.join(get_package_prefix({package!r}), 'lib', {package!r})
found = [os.path.join(d, f) for d, _, fs in os.walk(base) for f in fs
         if f == {executable!r} and os.access(os.path.join(d, f), os.X_OK)]
print('\\n'.join(found))
"""
    return [Path(p) for p in run_python(env, code).splitlines()]


def test_ros2_run_finds_the_node_and_it_runs(workspace, sourced_env):
    lib = workspace / "install" / "muscle_actuator" / "lib" / "muscle_actuator"
    assert ros2_run_executable(sourced_env, "muscle_actuator", "node") == [lib / "node"]

    r = subprocess.run([str(lib / "node"), "--help"], env=sourced_env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=30)
    assert r.returncode == 0, r.stdout
    assert r.stdout.startswith("usage: muscle_actuator node [--ros-args"), r.stdout

    r = subprocess.run([str(lib / "muscle_actuator"), "--help"], env=sourced_env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=30)
    assert r.returncode == 0, r.stdout
    assert "Run the ROS 2 node" in r.stdout, r.stdout
    # the installed binary is the node under test, not another build
    assert (lib / "muscle_actuator").read_bytes() == node_binary().read_bytes()


def test_messages_import_from_the_install(workspace, sourced_env):
    got = run_python(sourced_env, """
from muscle_actuator_msgs.msg import ActuatorState
from rclpy.serialization import serialize_message, deserialize_message
import muscle_actuator_msgs
m = ActuatorState(model='hill', joint=['elbow'], position=[0.25])
assert deserialize_message(serialize_message(m), ActuatorState) == m
print(muscle_actuator_msgs.__file__)
""")
    assert Path(got).is_relative_to(workspace / "install" / "muscle_actuator_msgs"), got
