"""`model` at start-up gives that model in ~/state.model, for every model the binary lists
(`muscle_actuator models`); the message's MODEL_* constants are those names; q0..q2 are non-zero
only for the Huxley models (Distribution-Moment states)."""

import subprocess
import time

import pytest

from muscle_actuator_msgs.msg import ActuatorState

from helpers import NodeProcess, Watch, muscle, finite_state


def listed_models():
    """The model names, in the binary's order: the first word of each line of `models`."""
    out = subprocess.run([NodeProcess.binary(), "models"], check=True, capture_output=True, text=True)
    return [line.split()[0] for line in out.stdout.splitlines() if line.strip()]


MODELS = listed_models()


def test_model_constants_are_the_parameter_values():
    constants = [getattr(ActuatorState, a) for a in dir(ActuatorState) if a.startswith("MODEL_")]
    assert sorted(constants) == sorted(MODELS) and len(MODELS) >= 3
    for m in MODELS:
        assert getattr(ActuatorState, "MODEL_" + m.upper().replace("-", "_")) == m


@pytest.mark.parametrize("model", MODELS)
def test_model_at_start_up(peer, model):
    ns = "/t_model_" + model.replace("-", "_")
    # The full Huxley model is the expensive reference: a slower tick keeps a debug build in time.
    rate = "250.0" if model == ActuatorState.MODEL_HUXLEY_PDE else "1000.0"
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
        if model == ActuatorState.MODEL_HILL:
            assert all(q == (0.0, 0.0, 0.0) for q in qs), qs
        else:
            assert all(all(abs(q) > 0.0 for q in triple) for triple in qs), qs
            assert muscle(last, "flexor").q0 > 0.0
        assert muscle(last, "flexor").force > muscle(first, "flexor").force
    finally:
        node.stop()
        assert node.returncode == 0, node.output()[-2000:]
