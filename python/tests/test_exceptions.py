"""The exception hierarchy (docs/python.md#errors): every error is a `ma.Error` (a ValueError) of
the kind of the mistake, with the message unchanged; missing files are FileNotFoundErrors, unknown
names KeyErrors; the classes pickle (Ray sends them back from workers)."""

from __future__ import annotations

import errno
import pickle

import numpy as np
import pytest

import muscle_actuator as ma
from test_errors import cli_error


def test_the_classes_and_their_bases():
    assert issubclass(ma.Error, ValueError)
    for kind in (ma.ConfigError, ma.InputError, ma.StepError, ma.RecordingError, ma.UnknownNameError, ma.FileNotFound):
        assert issubclass(kind, ma.Error) and issubclass(kind, ValueError), kind
        assert kind.__module__ == "muscle_actuator" and kind.__doc__
        assert getattr(ma._core, kind.__name__) is kind
    assert issubclass(ma.UnknownNameError, KeyError)
    assert issubclass(ma.FileNotFound, FileNotFoundError) and issubclass(ma.FileNotFound, OSError)
    assert issubclass(ma.StepError, RuntimeError)
    # the kinds are distinct
    assert not issubclass(ma.ConfigError, ma.InputError) and not issubclass(ma.InputError, ma.ConfigError)
    assert not issubclass(ma.UnknownNameError, FileNotFoundError)
    # KeyError's quoting is not applied: the message reads as the command line prints it
    assert str(ma.UnknownNameError("unknown x")) == "unknown x"


def raised(fn, *args, **kwargs) -> BaseException:
    with pytest.raises(Exception) as e:
        fn(*args, **kwargs)
    return e.value


def test_configuration_errors():
    for call in [
        lambda: ma.Actuator({"muscle": [{"name": "flexor", "k_tt": 1.0}]}),
        lambda: ma.Actuator(overrides={"muscle.flexor.k_tt": 1.0}),
        lambda: ma.Actuator(overrides={"muscle.flexor.k_t": -5.0}),
        lambda: ma.Actuator(overrides=[1]),
        lambda: ma.Actuator(rate_hz=0.0),
        lambda: ma.Actuator(substeps=-1),
        lambda: ma.Actuator(config=3.5),
        lambda: ma.rollout("elbow", "hill", np.zeros((1, 2, 2)), threads=0),
        lambda: ma.rollout("elbow", "hill", np.zeros((2, 3, 2)), overrides=[{}]),
        lambda: ma.rollout([ma.Actuator()], excitation=np.zeros((1, 2, 2)), overrides=[{}]),
        lambda: ma.Actuator("arm", "hill").set_state(ma.Actuator("elbow", "hill").get_state()),
    ]:
        assert type(raised(call)) is ma.ConfigError


def test_a_batch_instance_keeps_its_class_and_says_which():
    e = raised(ma.rollout, "elbow", "hill", np.zeros((2, 3, 2)), overrides=[{}, {"muscle.flexor.k_t": -1.0}])
    assert type(e) is ma.ConfigError and str(e).startswith("instance 1: ")
    e = raised(ma.rollout, "elbow", "hill", np.zeros((2, 3, 2)), overrides=[{}, {"muscle.x.k_t": 1.0}])
    assert type(e) is ma.UnknownNameError and str(e).startswith("instance 1: ")
    e = raised(ma.rollout, "elbow", "hux", np.zeros((1, 3, 2)))
    assert type(e) is ma.UnknownNameError


def test_input_errors():
    a = ma.Actuator("elbow", "hill")
    for call in [
        lambda: a.step(excitation=[0.1, 0.2, 0.3]),
        lambda: a.step(excitation=[0.1, float("nan")]),
        lambda: a.step(excitation="high"),
        lambda: a.step(excitation={"flexor": float("inf")}),
        lambda: a.step(ticks=-1),
        lambda: a.rollout(np.zeros((3, 3))),
        lambda: a.rollout(np.zeros((3, 2)), outputs=["force", "force"]),
        lambda: ma.rollout([a, a], excitation=np.zeros((2, 2, 2))),
        lambda: ma.rollout("elbow", "hill", np.zeros((2, 2))),
        lambda: ma.rollout("elbow", "hill", None),
        lambda: ma.Actuator("arm", "hill").set_joint_motion("elbow", 0.1),
    ]:
        assert type(raised(call)) is ma.InputError
    assert a.tick == 0


def test_unknown_names(cli):
    a = ma.Actuator("elbow", "hill")
    cases = [
        (lambda: ma.Actuator("elbow", "hux"), ("simulate", "pulse", "--model", "hux")),
        (lambda: ma.simulate("pulse", energy_model="kleiber"), ("simulate", "pulse", "--energy-model", "kleiber")),
        (lambda: ma.simulate("no-such-scenario"), ("simulate", "no-such-scenario")),
    ]
    for call, args in cases:
        e = raised(call)
        assert type(e) is ma.UnknownNameError and isinstance(e, KeyError)
        assert str(e) == cli_error(cli, *args)
    for call, msg in [
        (lambda: a.step(excitation={"biceps": 1.0}), 'excitation: unknown name "biceps"'),
        (lambda: a.set_joint_motion("knee", 0.1), "unknown joint knee"),
        (lambda: a.rollout(np.zeros((3, 2)), outputs=["forces"]), 'unknown output "forces"'),
        (lambda: ma.simulate("pulse", model="hill")["forces"], "unknown output 'forces'"),
        (lambda: ma.simulate("pulse", model="hill").muscle("biceps"), "unknown muscle 'biceps'"),
        (lambda: ma.Actuator(overrides={"muscle.biceps.k_t": 1.0}), 'overrides: override "muscle.biceps.k_t": no muscle named "biceps"'),
    ]:
        e = raised(call)
        assert type(e) is ma.UnknownNameError and str(e).startswith(msg), str(e)
    # a KeyError, as a dict's lookup
    with pytest.raises(KeyError):
        ma.simulate("pulse", model="hill")["forces"]


def test_missing_files_are_file_not_found_errors(cli, tmp_path):
    missing = tmp_path / "missing.mcap"
    for call, args in [
        (lambda: ma.read_recording(missing), ("export", "--csv", "-", str(missing))),
        (lambda: ma.simulate("pulse", config=tmp_path / "no-such.toml"), ("simulate", "pulse", "--config", str(tmp_path / "no-such.toml"))),
        (lambda: ma.Actuator("elbw"), ("simulate", "pulse", "--config", "elbw")),
        (lambda: ma.simulate(str(tmp_path / "no-such-scenario.toml")), ("simulate", str(tmp_path / "no-such-scenario.toml"))),
    ]:
        e = raised(call)
        assert type(e) is ma.FileNotFound and isinstance(e, FileNotFoundError), (args, type(e))
        assert e.errno == errno.ENOENT
        assert str(e) == cli_error(cli, *args)
    e = raised(ma.compare, missing, missing)
    assert type(e) is ma.FileNotFound


def test_recording_errors_and_os_errors(cli, tmp_path):
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(b"\x89MCAP0\r\n" + b"\0" * 64)
    e = raised(ma.read_recording, bad)
    assert type(e) is ma.RecordingError and str(e) == cli_error(cli, "export", "--csv", "-", str(bad))
    assert type(raised(ma.compare, bad, bad)) is ma.RecordingError
    # an output that cannot be written: OSError, not an Error of the package
    ma.simulate("pulse", model="hill", out=tmp_path / "ok.mcap")
    e = raised(ma.simulate, "pulse", model="hill", out=tmp_path / "ok.mcap" / "x.mcap")  # under a file
    assert type(e) is OSError, (type(e), e)
    e = raised(ma.compare, tmp_path / "ok.mcap", tmp_path / "ok.mcap", plot=tmp_path / "ok.mcap" / "x.png")
    assert isinstance(e, OSError) and not isinstance(e, ma.Error), (type(e), e)  # matplotlib's


def test_a_bad_scenario_file_is_a_configuration_error(cli, tmp_path):
    sc = tmp_path / "bad.toml"
    sc.write_text("duration = -1.0\n")
    e = raised(ma.simulate, sc)
    assert type(e) is ma.ConfigError and str(e) == cli_error(cli, "simulate", str(sc))
    # a configuration file that is not UTF-8 text: its content is wrong, not its access
    cfg = tmp_path / "latin1.toml"
    cfg.write_bytes(b"[[joint]]\nname = \"\xe9\"\n")
    e = raised(ma.Actuator, cfg)
    assert type(e) is ma.ConfigError and str(e) == cli_error(cli, "simulate", "pulse", "--config", str(cfg))


def test_errors_pickle_with_their_class_and_attributes():
    e = raised(ma.read_recording, "missing.mcap")
    back = pickle.loads(pickle.dumps(e))
    assert type(back) is ma.FileNotFound and str(back) == str(e)
    a = ma.Actuator("elbow", "hill", substeps=1, overrides={"muscle.*.k_t": 1e12, "joint.elbow.inertia": 1e-9})
    with pytest.raises(ma.StepError) as s:
        for _ in range(2000):
            a.step(excitation=[1.0, 0.0], external_torque=[1e6])
    assert isinstance(s.value, RuntimeError) and isinstance(s.value, ValueError)
    back = pickle.loads(pickle.dumps(s.value))
    assert type(back) is ma.StepError and (back.tick, back.reason) == (s.value.tick, s.value.reason)
