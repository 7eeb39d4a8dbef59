"""A parameter sweep on Ray workers (a local cluster of 2 CPUs on 127.0.0.1) gives the same arrays
as the same sweep in this process: configurations, actuators and results cross processes by
pickle, and nothing depends on where a task runs."""

from __future__ import annotations

import sys

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import assert_bits_equal

ray = pytest.importorskip("ray")

TENDON = np.geomspace(5e4, 5e5, 6)


def sweep_point(k_t: float) -> dict[str, np.ndarray]:
    """A co-contraction step of the elbow with both tendons' stiffness k_t."""
    u = np.zeros((1, 400, 2))
    u[:, 50:, :] = 0.5
    out = ma.rollout("elbow", "huxley", u, overrides=[{"muscle.*.k_t": float(k_t)}],
                     outputs=["force", "fiber_length", "joint.stiffness"], threads=1)
    return {k: v[0] for k, v in out.items()}


def resume(actuator: ma.Actuator) -> np.ndarray:
    return actuator.rollout(np.full((100, 6), 0.8), outputs=["force"])["force"]


@pytest.fixture(scope="module")
def cluster():
    # The workers cannot import this test module: its functions travel by value, as a
    # notebook's do.
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    ray.init(num_cpus=2, include_dashboard=False, _node_ip_address="127.0.0.1",
             log_to_driver=False, configure_logging=False)
    yield
    ray.shutdown()


def test_a_sweep_on_ray_equals_the_local_loop(cluster):
    local = [sweep_point(k) for k in TENDON]
    remote_fn = ray.remote(sweep_point)
    remote = ray.get([remote_fn.remote(k) for k in TENDON])
    for k, (a, b) in enumerate(zip(local, remote)):
        for name in a:
            assert_bits_equal(a[name], b[name], f"k_t[{k}] {name}")
    # the sweep did something: stiffer tendons, stiffer joint
    j = [r["joint.stiffness"][-1, 0] for r in local]
    assert all(x < y for x, y in zip(j, j[1:]))


def test_an_actuator_sent_to_a_worker_resumes_there_bit_for_bit(cluster):
    a = ma.Actuator("arm", "huxley")
    a.step(excitation=np.full(6, 0.4), ticks=120)
    want = resume(a.copy())
    got = ray.get(ray.remote(resume).remote(a))
    assert_bits_equal(got, want, "resumed on a worker")
