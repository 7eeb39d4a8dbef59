"""The built-in configuration `arm` (OpenSim's arm26: joints shoulder and elbow, six muscles)
through DDS: the state's per-joint arrays and 2x2 stiffness matrix, joint_states of both joints,
commands by muscle name (a biarticular muscle moves and couples both joints), an unknown muscle
name rejected whole, an external load by joint name. One node (Huxley DM, the default model)."""

import time

import pytest

from helpers import NodeProcess, Watch, muscle, finite_state, wait_until

NS = "/t_limb"
JOINTS = ["shoulder", "elbow"]
MUSCLES = ["TRIlong", "TRIlat", "TRImed", "BIClong", "BICshort", "BRA"]


@pytest.fixture(scope="module")
def node():
    n = NodeProcess(NS, ["-p", "config:=arm", "-p", "publish_rate_hz:=100.0"])
    n.start()
    try:
        yield n
    finally:
        n.stop()
        assert n.returncode == 0, n.output()[-2000:]


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node, rosout=True)


@pytest.fixture
def fresh(peer, node, watch):
    """Each test starts from the initial state with no input."""
    r = peer.reset(node)
    assert r.success, r.message
    return watch


def assert_symmetric(k):
    """K_se == K_es exactly (docs/model.md §8b: K is symmetric; the node adds the same product
    k_mtu (r_j r_l) to both entries)."""
    assert k[1] == k[2], f"stiffness matrix not symmetric: {k} ({k[1] - k[2]:+.3g})"


def excitations(state):
    return {m.name: m.excitation for m in state.muscles}


def load_until_seen(peer, node, watch, joints, torques, timeout=10.0):
    """Sends an external load by joint name until ~/state shows it in force (the first sample
    can be lost while the new writer is being matched); returns that state."""
    topic = node.topic("~/external_load")
    want = dict(zip(joints, torques))
    deadline = time.monotonic() + timeout
    while True:
        t = time.monotonic()
        peer.load(topic, joints, torques)
        try:
            return watch.state.wait(
                lambda s: all(s.external_torque[s.joint.index(j)] == v for j, v in want.items()),
                timeout=0.5,
                since=t,
                what=f"external load {want}",
            )
        except AssertionError:
            if time.monotonic() > deadline:
                raise AssertionError(f"timed out after {timeout} s waiting for load {want}")


def test_arm_state_and_joint_states_carry_both_joints_and_six_muscles(fresh):
    w = fresh
    t0 = time.monotonic()
    s = w.next_state()
    assert s.model == "huxley"
    assert list(s.joint) == JOINTS
    for field in ("position", "velocity", "torque", "external_torque", "stiffness"):
        assert len(getattr(s, field)) == 2, f"{field}: {list(getattr(s, field))}"
    assert len(s.stiffness_matrix) == 4, list(s.stiffness_matrix)
    k = list(s.stiffness_matrix)
    assert_symmetric(k)
    assert [k[0], k[3]] == list(s.stiffness), (k, list(s.stiffness))
    assert [m.name for m in s.muscles] == MUSCLES
    assert finite_state(s)
    # /joint_states (in the node's namespace) names both joints; a state and a joint_states
    # message of the same sample agree.
    js = w.joints.wait(since=t0, what=f"{w.node.topic('joint_states')}")
    assert list(js.name) == JOINTS
    assert len(js.position) == 2 and len(js.velocity) == 2 and len(js.effort) == 2

    def matched_pair():
        states = {(m.header.stamp.sec, m.header.stamp.nanosec): m for m in w.state.msgs(t0)}
        for j in w.joints.msgs(t0):
            st = states.get((j.header.stamp.sec, j.header.stamp.nanosec))
            if st is not None:
                return j, st
        return None

    j, st = wait_until(matched_pair, 10.0, what="a joint_states message matching a state")
    assert list(j.name) == list(st.joint)
    assert list(j.position) == list(st.position)
    assert list(j.velocity) == list(st.velocity)
    assert list(j.effort) == list(st.torque)


def run_from_reset(peer, node, w, ticks, **excitation):
    """Resets the node, optionally commands `excitation`, and collects the states (by tick) until
    `ticks` ticks after the command took effect (after the reset if none). Returns (the state
    in force when the command was first seen or None, {tick: state})."""
    # The clock starts before the request: the node may publish its first ticks after the
    # reset before the answer reaches us (a loaded machine), and those states count.
    t = time.monotonic()
    r = peer.reset(node)
    assert r.success, r.message
    marker = w.state.wait(lambda s: s.tick <= 20, since=t, what="a state just after reset")
    # States come in order from one writer: everything received from the marker on is after
    # the reset (states of before the reset, received after `t`, have larger ticks).
    t_marker = next(tt for (tt, m) in w.state.timed(t) if m is marker)
    on = w.activation(**excitation) if excitation else None
    end = (on.tick if on else 0) + ticks
    w.state.wait(lambda s: s.tick >= end, since=t_marker, timeout=10.0, what=f"tick {end}")
    return on, {m.tick: m for (tt, m) in w.state.timed(t_marker) if m.tick <= end}


def test_biclong_moves_both_joints_and_couples_them(peer, node, watch):
    w = watch
    # 0.4 s of BIClong at 0.5 after a reset, and the same ticks with no input: the arm's
    # initial state is not a joint equilibrium (it drifts on its own, towards positive angles),
    # so the command's effect is measured against that drift as well as against the start.
    on, cmd = run_from_reset(peer, node, w, 400, BIClong=0.5)
    end = max(cmd)
    _, base = run_from_reset(peer, node, w, end)
    assert end in base, f"no state at tick {end} without input: {sorted(base)[-3:]}"
    assert all(finite_state(s) for s in cmd.values())
    before = cmd[max(k for k in cmd if k < on.tick)]
    after, drift = cmd[end], base[end]
    assert end - on.tick >= 300, (on.tick, end)
    assert muscle(before, "BIClong").excitation == 0.0
    # Only BIClong is excited.
    expected = {n: 0.0 for n in MUSCLES}
    expected["BIClong"] = 0.5
    assert excitations(after) == expected
    # It pulls (the force falls again as the joints swing and the muscle shortens).
    peak = max(muscle(s, "BIClong").force for t, s in cmd.items() if t >= on.tick)
    assert peak > 2 * max(muscle(s, "BIClong").force for s in base.values()), peak
    # Its moment arms are positive at both joints: both angles increase, and by far more than
    # they drift with no input.
    for j, name in enumerate(JOINTS):
        moved = after.position[j] - before.position[j]
        assert moved > 1e-3, f"{name} moved {moved} rad"
        extra = after.position[j] - drift.position[j]
        assert extra > 0.05, (
            f"{name}: {after.position[j]} rad with BIClong, {drift.position[j]} rad without"
        )
    # A biarticular muscle under tension couples the joints: K_se = K_es, far larger than with
    # no input (r_s r_e > 0 for BIClong; passive biarticular muscles give a little already).
    k, k0 = list(after.stiffness_matrix), list(drift.stiffness_matrix)
    assert_symmetric(k)
    assert k[1] != 0.0, f"no coupling: {k}"
    assert k[1] > 5 * abs(k0[1]), f"off-diagonal stiffness {k0[1]} without input, {k[1]} with BIClong"


def counters(watch):
    return watch.diagnostics()["inputs"]


def test_unknown_muscle_name_is_rejected_whole(peer, node, fresh):
    w = fresh
    w.activation(BIClong=0.2)
    w.next_state()  # in force
    before = counters(w)
    t_cmd = time.monotonic()
    # `flexor` exists only in the default elbow configuration; `BIClong` is valid, and must not
    # be applied either.
    peer.raw_activation(node.topic("~/activation"), ["BIClong", "flexor"], [0.9, 0.9])

    def rejected():
        d = counters(w)
        return d if int(d["rejected_unknown_name"]) > int(before["rejected_unknown_name"]) else None

    after = wait_until(rejected, 10.0, what="diagnostics rejected_unknown_name to grow")
    assert int(after["activation_rejected"]) > int(before["activation_rejected"])
    assert after["_level"] == 1  # WARN in the period with a rejection
    assert after["last_problem"].startswith("activation command rejected")
    assert "flexor" in after["last_problem"]
    # The names it is checked against are the arm's.
    assert "BIClong" in after["last_problem"], after["last_problem"]
    w.rosout.wait(
        lambda m: "rejected" in m.msg and "flexor" in m.msg and m.name.endswith("muscle_actuator"),
        timeout=10.0,
        since=t_cmd,
        what="a /rosout warning naming the unknown muscle",
    )
    # Nothing of it applied: the command in force stays.
    s = w.next_state()
    expected = {n: 0.0 for n in MUSCLES}
    expected["BIClong"] = 0.2
    assert excitations(s) == expected
    assert list(s.external_torque) == [0.0, 0.0]
    assert all(muscle(x, "BIClong").excitation == 0.2 for x in w.state.msgs(t_cmd))


def test_external_load_by_joint_name_reaches_that_joint_only(peer, node, fresh):
    w = fresh
    s = load_until_seen(peer, node, w, ["elbow"], [0.7])
    assert list(s.external_torque) == [0.0, 0.7]
    later = w.states_after(time.monotonic(), 0.3)
    assert later and all(list(x.external_torque) == [0.0, 0.7] for x in later)
    # And the shoulder by its name, leaving the elbow's load as it was.
    s = load_until_seen(peer, node, w, ["shoulder"], [-0.4])
    assert list(s.external_torque) == [-0.4, 0.7]
