"""`model` at start-up gives that model in ~/state.model; q0..q2 are non-zero only for the
Huxley models (Distribution-Moment states)."""

import time

import pytest

from muscle_actuator_msgs.msg import ActuatorState

from helpers import NodeProcess, Watch, muscle, finite_state

# The message's own constants name the models.
MODELS = [ActuatorState.MODEL_HILL, ActuatorState.MODEL_HUXLEY, ActuatorState.MODEL_HUXLEY_PDE]


def test_model_constants_are_the_parameter_values():
    assert MODELS == ["hill", "huxley", "huxley-pde"]


@pytest.mark.parametrize("model", MODELS)
def test_model_at_start_up(peer, model):
    ns = "/t_model_" + model.replace("-", "_")
    # The full Huxley model is the expensive reference: a slower tick keeps a debug build in time.
    rate = "250.0" if model == "huxley-pde" else "1000.0"
    node = NodeProcess(ns, ["-p", f"model:={model}", "-p", f"rate_hz:={rate}", "-p", "publish_rate_hz:=50.0"])
    node.start()
    try:
        w = Watch(peer, node, diagnostics=False)
        first = w.state.wait(timeout=20.0)
        assert first.model == model
        w.activation(flexor=0.8, extensor=0.4)
        # The window starts once the command is in force (it may take a resend to get there).
        states = w.states_after(time.monotonic(), 0.4)
        assert states and all(s.model == model for s in states)
        assert all(finite_state(s) for s in states)
        last = states[-1]
        qs = [(m.q0, m.q1, m.q2) for m in last.muscles]
        if model == "hill":
            assert all(q == (0.0, 0.0, 0.0) for q in qs), qs
        else:
            assert all(all(abs(q) > 0.0 for q in triple) for triple in qs), qs
            assert muscle(last, "flexor").q0 > 0.0
        assert muscle(last, "flexor").force > muscle(first, "flexor").force
    finally:
        node.stop()
        assert node.returncode == 0, node.output()[-2000:]
