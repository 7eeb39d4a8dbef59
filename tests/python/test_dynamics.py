"""The actuator through DDS: a flexor step, joint_states against ~/state, external torque,
co-contraction and joint stiffness, reset. One node (Huxley DM, the default model)."""

import math
import time

import pytest

from helpers import Watch, muscle, finite_state, wait_until

NS = "/t_dyn"


@pytest.fixture(scope="module")
def node(node_factory):
    return node_factory(NS, "-p", "publish_rate_hz:=500.0")


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node, diagnostics=False)


@pytest.fixture
def fresh(peer, node, watch):
    """Each test starts from the initial state with no input."""
    r = peer.reset(node)
    assert r.success, r.message
    return watch


def settled(watch, seconds):
    t0 = time.monotonic()
    states = watch.states_after(t0, seconds)
    assert states, "no state received"
    return states[-1]


def test_flexor_step_raises_flexor_force_and_flexes_the_joint(fresh):
    w = fresh
    rest = w.next_state()
    assert rest.model == "huxley"
    f_rest = muscle(rest, "flexor").force
    t0 = time.monotonic()
    w.activation(flexor=1.0, extensor=0.0)
    states = w.states_after(t0, 0.6)
    assert all(finite_state(s) for s in states)
    on = [s for s in states if muscle(s, "flexor").excitation == 1.0]
    assert on, "the command never took effect"
    forces = [muscle(s, "flexor").force for s in on]
    ticks = [s.tick for s in on]
    # The first peak (the force then falls while the joint swings, and settles higher later).
    peak = next((i for i in range(1, len(forces) - 1) if forces[i + 1] <= forces[i]), None)
    assert peak is not None, f"the force never peaked: {forces[:20]}"
    # Rises far above rest, within the time scale of activation and cross-bridge attachment
    # (tens of ms), and smoothly (Huxley): several samples on the way up, none a jump from
    # rest to the peak.
    assert forces[peak] > 200.0 and forces[peak] > 20 * max(f_rest, 1e-3), forces[: peak + 1]
    peak_ms = (ticks[peak] - ticks[0]) * 1e3 / 1000.0
    assert 2.0 <= peak_ms <= 100.0, f"force peaked {peak_ms} ms after the step"
    rise = forces[: peak + 1]
    assert len(rise) >= 4, f"force rose in {len(rise)} samples only: not smooth"
    assert max(b - a for a, b in zip(rise, rise[1:])) < 0.8 * forces[peak], rise
    assert max(forces) >= forces[peak]
    # Positive joint motion, and the extensor stays unexcited.
    assert on[-1].position[0] > 0.1, f"joint did not flex: {on[-1].position[0]}"
    assert max(s.velocity[0] for s in on) > 0.0
    assert muscle(on[-1], "extensor").excitation == 0.0


def test_joint_states_agree_with_state(fresh):
    w = fresh
    t0 = time.monotonic()
    w.activation(flexor=0.7, extensor=0.1)
    w.states_after(t0, 0.4)
    states = {(s.header.stamp.sec, s.header.stamp.nanosec): s for s in w.state.msgs(t0)}
    joints = [j for j in w.joints.msgs(t0)]
    matched = 0
    for j in joints:
        s = states.get((j.header.stamp.sec, j.header.stamp.nanosec))
        if s is None:
            continue
        matched += 1
        assert list(j.name) == list(s.joint)
        assert list(j.position) == list(s.position)
        assert list(j.velocity) == list(s.velocity)
        assert list(j.effort) == list(s.torque)  # effort = net muscle torque
    assert matched >= 50, f"only {matched} joint_states matched a state"
    assert any(abs(s.position[0]) > 1e-3 for s in states.values()), "the joint never moved"


@pytest.mark.parametrize("torque", [2.0, -2.0])
def test_external_torque_moves_the_joint_its_way(fresh, torque):
    w = fresh
    start = w.next_state().position[0]
    w.load(torque)
    s = settled(w, 0.5)
    assert s.external_torque[0] == torque
    moved = s.position[0] - start
    assert math.copysign(1.0, moved) == math.copysign(1.0, torque), f"moved {moved} rad"
    assert abs(moved) > 0.05


def test_co_contraction_raises_joint_stiffness(fresh):
    w = fresh
    w.activation(flexor=0.1, extensor=0.1)
    low = settled(w, 0.6)
    w.activation(flexor=0.6, extensor=0.6)
    high = settled(w, 0.6)
    k_low, k_high = low.stiffness[0], high.stiffness[0]
    assert k_low > 0
    assert k_high > 1.2 * k_low, f"stiffness {k_low} -> {k_high}"
    # Balanced co-contraction holds the joint near its rest angle.
    assert abs(high.position[0]) < 0.05


def state_after_reset(w, t_reset, what):
    """The first state received after `t_reset` whose tick falls below the one before it: the
    tick count starts again from 1 at a reset, so this is a state after the reset whichever of
    the first ticks' states a loaded reader took (the keep-last writer may overwrite some)."""

    def find():
        before = None
        for t, m in w.state.timed():
            if before is not None and t >= t_reset and m.tick < before:
                return m
            before = m.tick
        return None

    return wait_until(find, 10.0, what=what)


def test_reset_returns_to_the_initial_state(peer, node, watch):
    w = watch
    w.state.wait(what="a state before the reset")
    # The clock starts before the request: the node may publish its first ticks after the
    # reset before the answer reaches us (a loaded machine), and those states count.
    t_reset = time.monotonic()
    r = peer.reset(node)
    assert r.success, r.message
    initial = state_after_reset(w, t_reset, "a state just after reset")
    w.activation(flexor=0.9, extensor=0.2)
    w.load(1.0)
    moved = settled(w, 0.4)
    assert abs(moved.position[0] - initial.position[0]) > 0.05
    t_reset = time.monotonic()
    r = peer.reset(node)
    assert r.success and "reset" in r.message
    after = state_after_reset(w, t_reset, "a state after reset")
    assert after.tick < moved.tick
    assert abs(after.position[0] - initial.position[0]) < 1e-6
    assert muscle(after, "flexor").excitation == 0.0
    assert after.external_torque[0] == 0.0
    # And it stays there with no input.
    later = settled(w, 0.3)
    assert abs(later.position[0] - initial.position[0]) < 1e-6
    assert abs(muscle(later, "flexor").force - muscle(initial, "flexor").force) < 1e-6
