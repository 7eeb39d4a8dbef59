"""The six parameters through rclpy's parameter client: listed, read, changed at run time,
and an invalid value refused with a reason. `-p` and `--params-file` at start-up."""

import time

import pytest
from rcl_interfaces.msg import ParameterEvent, ParameterType
from rclpy.parameter import Parameter, parameter_value_to_python

from helpers import NodeProcess, Watch, SERVICE_TIMEOUT, reliable, wait_until

NS = "/t_params"
SIX = {"model", "rate_hz", "publish_rate_hz", "config", "record", "record_dir"}


@pytest.fixture(scope="module")
def params_file(tmp_path_factory):
    p = tmp_path_factory.mktemp("params") / "node.yaml"
    p.write_text(
        "/**:\n  ros__parameters:\n    record: false\n"
        "/t_params/muscle_actuator:\n  ros__parameters:\n    record_dir: /tmp/from_file\n"
        "    model: huxley\n"
    )
    return p


@pytest.fixture(scope="module")
def node(node_factory, params_file):
    # -p after --params-file wins for `model`.
    return node_factory(
        NS, "--params-file", str(params_file), "-p", "model:=hill", "-p", "publish_rate_hz:=100.0"
    )


@pytest.fixture(scope="module")
def client(peer, node):
    return peer.param_client(node)


@pytest.fixture(scope="module")
def watch(peer, node):
    return Watch(peer, node, diagnostics=False)


def values(peer, client, names):
    # A get is idempotent: asked again if the first answer is lost (a request sent to a node that
    # has just started can reach it before its reply writer has matched this client).
    for attempt in range(3):
        fut = client.get_parameters(names)
        try:
            resp = peer.await_future(fut, timeout=5.0 if attempt < 2 else 15.0)
            break
        except AssertionError:
            if attempt == 2:
                raise
    return {n: parameter_value_to_python(v) for n, v in zip(names, resp.values)}


def test_six_parameters_are_listed(peer, client):
    resp = peer.await_future(client.list_parameters())
    assert SIX <= set(resp.result.names)


def test_values_from_the_command_line_and_the_file(peer, client):
    v = values(peer, client, sorted(SIX))
    assert v["model"] == "hill"  # -p overrides the file
    assert v["rate_hz"] == 1000.0
    assert v["publish_rate_hz"] == 100.0
    assert v["config"] == ""
    assert v["record"] is False  # from /** in the file
    assert v["record_dir"] == "/tmp/from_file"
    types = peer.await_future(client.get_parameter_types(["model", "rate_hz", "record"]))
    assert list(types.types) == [
        ParameterType.PARAMETER_STRING,
        ParameterType.PARAMETER_DOUBLE,
        ParameterType.PARAMETER_BOOL,
    ]


@pytest.mark.parametrize(
    "name,value,reason",
    [
        ("rate_hz", -1.0, "rate_hz"),
        ("rate_hz", 0.0, "rate_hz"),
        ("model", "bogus", "bogus"),
        ("config", "/nonexistent/actuator.toml", "/nonexistent/actuator.toml"),
        ("publish_rate_hz", -5.0, "publish_rate_hz"),
        ("rate_hz", "fast", "rate_hz"),
        ("energy_model", "bogus", "bogus"),
    ],
)
def test_invalid_values_are_refused_with_a_reason(peer, client, name, value, reason):
    before = values(peer, client, [name])[name]
    resp = peer.await_future(client.set_parameters([Parameter(name, value=value)]))
    (result,) = resp.results
    assert not result.successful
    assert reason in result.reason, result.reason
    assert values(peer, client, [name])[name] == before


def test_model_changes_at_run_time(peer, client, watch):
    # The subscription stays for the module: destroying it while the peer's executor waits on
    # it in another thread is a race inside rclpy.
    events = peer.subscribe(ParameterEvent, "/parameter_events", reliable(10))
    try:
        resp = peer.await_future(client.set_parameters([Parameter("model", value="huxley")]))
        assert resp.results[0].successful, resp.results[0].reason
        watch.next_state(lambda s: s.model == "huxley", what="~/state with model huxley")
        events.wait(
            lambda e: e.node == f"{NS}/muscle_actuator"
            and any(p.name == "model" and p.value.string_value == "huxley" for p in e.changed_parameters),
            SERVICE_TIMEOUT,
            what="the change on /parameter_events",
        )
    finally:
        peer.await_future(client.set_parameters([Parameter("model", value="hill")]))
    watch.next_state(lambda s: s.model == "hill", what="~/state back to hill")


def test_energy_model_changes_at_run_time(peer, client, watch):
    """`energy_model`: empty by default (each muscle's from the configuration); a change
    rebuilds the actuator, whose states carry the energetics: the parts sum to the metabolic
    power, the energy since the start grows, Hill's metabolic power is its phenomenological
    model's."""
    assert values(peer, client, ["energy_model"])["energy_model"] == ""
    try:
        resp = peer.await_future(client.set_parameters([Parameter("energy_model", value="bhargava")]))
        assert resp.results[0].successful, resp.results[0].reason
        assert values(peer, client, ["energy_model"])["energy_model"] == "bhargava"
        first = watch.next_state(lambda s: s.model == "hill" and 0 < s.tick < 200, what="a state of the rebuilt actuator")
        later = watch.next_state(lambda s: s.tick > first.tick + 50, what="a later state")
        for s in (first, later):
            for m in s.muscles:
                parts = m.activation_heat_rate + m.shortening_heat_rate + m.work_rate + m.bridge_storage_rate
                assert abs(parts - m.metabolic_power) <= 1e-9 * max(1.0, abs(m.metabolic_power))
                assert m.metabolic_power == m.phenomenological_power
                assert m.bridge_storage_rate == 0.0
                # At rest the heat floor of 1 W/kg of the 1.59 kg muscle.
                assert m.metabolic_power >= 1.59
        for a, b in zip(first.muscles, later.muscles):
            assert b.metabolic_energy > a.metabolic_energy > 0.0
    finally:
        peer.await_future(client.set_parameters([Parameter("energy_model", value="")]))
    assert values(peer, client, ["energy_model"])["energy_model"] == ""


def test_publish_rate_changes_the_state_rate(peer, client, watch):
    def rate(seconds=1.0):
        t0 = time.monotonic()
        states = watch.states_after(t0, seconds)
        return len(states) / seconds

    assert 70 <= rate() <= 130
    resp = peer.await_future(client.set_parameters([Parameter("publish_rate_hz", value=20.0)]))
    assert resp.results[0].successful, resp.results[0].reason
    time.sleep(0.2)
    assert 12 <= rate() <= 30
    peer.await_future(client.set_parameters([Parameter("publish_rate_hz", value=100.0)]))


def test_bad_start_up_parameter_is_one_clear_error():
    for args, word in [
        (["-p", "model:=bogus"], "bogus"),
        (["-p", "rate_hz:=-3"], "rate_hz"),
        (["-p", "colour:=red", "-p", "record:=maybe"], "record"),
        (["--params-file", "/nonexistent/p.yaml"], "/nonexistent/p.yaml"),
    ]:
        n = NodeProcess("/t_params_bad", args)
        n.start()
        rc = n.proc.wait(timeout=20)
        out = n.output().strip()
        assert rc != 0, out
        assert word in out, out
        assert "panicked" not in out, out


def started_with_file(node_factory, peer, namespace, text, tmp_path, *extra):
    """A node started with a parameters file holding `text`, and its parameter client."""
    f = tmp_path / "shared.yaml"
    f.write_text(text)
    n = node_factory(namespace, "--params-file", str(f), *extra)
    return n, peer.param_client(n)


def test_shared_file_with_other_nodes_parameters(node_factory, peer, tmp_path):
    # `/**` holds parameters of other nodes too; `-p` names one nobody declared. Both are
    # ignored (a debug-level note each) and the node's own values apply.
    n, c = started_with_file(
        node_factory,
        peer,
        "/t_params_shared",
        "/**:\n  ros__parameters:\n    robot_name: r2\n    use_sim_time: false\n"
        "    rate_hz: 500.0\n"
        "/camera:\n  ros__parameters:\n    exposure: 0.01\n",
        tmp_path,
        "-p", "colour:=red", "--log-level", "debug",
    )
    v = values(peer, c, ["rate_hz", "model"])
    assert v == {"rate_hz": 500.0, "model": "huxley"}
    assert n.alive()
    wait_until(lambda: "robot_name" in n.output(), 5.0, what="the debug note")
    out = n.output()
    assert "ignoring undeclared parameter \"robot_name\"" in out, out
    assert "ignoring undeclared parameter \"colour\"" in out, out
    assert "exposure" not in out, out  # another node's section is not read at all


def test_nested_namespace_layout(node_factory, peer, tmp_path):
    # The layout of the rcl documentation: namespace, then node name, then ros__parameters.
    n, c = started_with_file(
        node_factory,
        peer,
        "/t_params_arm",
        "/t_params_arm:\n"
        "  muscle_actuator:\n    ros__parameters:\n      model: hill\n      rate_hz: 250.0\n"
        "  other_node:\n    ros__parameters:\n      model: huxley-pde\n",
        tmp_path,
    )
    assert values(peer, c, ["model", "rate_hz"]) == {"model": "hill", "rate_hz": 250.0}


def test_key_without_slash_is_the_root_namespace_only(node_factory, peer, tmp_path):
    n, c = started_with_file(
        node_factory,
        peer,
        "/t_params_noslash",
        "muscle_actuator:\n  ros__parameters:\n    model: hill\n"
        "/**:\n  ros__parameters:\n    publish_rate_hz: 50.0\n",
        tmp_path,
    )
    v = values(peer, c, ["model", "publish_rate_hz"])
    assert v == {"model": "huxley", "publish_rate_hz": 50.0}
