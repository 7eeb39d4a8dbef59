"""Subjects, predictions, calibration and EMG from Python (docs/python.md "Subjects, EMG and
calibration"): `predict` gives the command line's CSV numbers bit for bit, `calibrate` is
repeatable for a seed (here and on Ray workers) and does not worsen the fit, a subject survives
TOML and pickle, bad inputs raise the package's exceptions, and the EMG chain recovers a known
envelope."""

from __future__ import annotations

import _thread
import importlib.util
import inspect
import pickle
import re
import signal
import sys
import threading

import numpy as np
import pytest

import muscle_actuator as ma
from conftest import ROOT, assert_bits_equal, read_csv

DATA = ROOT / "data" / "ceinms"
SUBJECT = DATA / "uncalibratedSubject.xml"
MAP = DATA / "emgGenerator-16To34.xml"
TRIAL = DATA / "_FastWalking_"
TWO_TRIALS = [DATA / "_FastWalking_", DATA / "_CrossOvers1_"]
KNEE = "R_knee_fe"


@pytest.fixture(scope="module")
def subject() -> ma.Subject:
    return ma.Subject.read(SUBJECT)


def columns(path) -> dict[str, np.ndarray]:
    header, rows = read_csv(path.read_text())
    values = np.array(rows, dtype=np.float64).T
    return dict(zip(header, values))


# --- (a) predict against the command line ------------------------------------------------


def test_predict_equals_the_command_lines_csv(cli, subject, tmp_path):
    moments_csv, muscles_csv = tmp_path / "moments.csv", tmp_path / "muscles.csv"
    out = cli("predict", "--subject", str(SUBJECT), "--excitations", str(MAP), "--trial", str(TRIAL),
              "--model", "hill", "--csv", str(moments_csv), "--muscles-csv", str(muscles_csv))
    p = ma.predict(subject, MAP, TRIAL, model="hill")
    want_m, want_u = columns(moments_csv), columns(muscles_csv)
    # The CSVs hold shortest round-trip floats, so their printing precision is every bit; the
    # command line and the extension must be built from the same sources.
    assert_bits_equal(p.time, want_m["time"], "time")
    assert p.dofs == sorted(p.dofs) and KNEE in p.dofs
    for dof in p.dofs:
        assert_bits_equal(p.measured[dof], want_m[f"{dof}_measured"], f"{dof}_measured")
        assert_bits_equal(p.moment[dof], want_m[dof], dof)
    n = len(p.time)
    for field in ("force", "activation", "fibre_length"):
        arr = getattr(p, field)
        assert arr.shape == (len(p.units), n)
        for i, unit in enumerate(p.units):
            assert_bits_equal(arr[i], want_u[f"{unit}.{field}"], f"{unit}.{field}")
    # to_pandas: the CSVs' columns, in their order, holding the arrays above
    moments, muscles = p.to_pandas()
    assert list(moments.columns) == list(want_m)
    assert list(muscles.columns) == list(want_u)
    for i, unit in enumerate(p.units):
        assert_bits_equal(muscles[f"{unit}.force"].to_numpy(), p.force[i], unit)
    for dof in p.dofs:
        assert_bits_equal(moments[dof].to_numpy(), want_m[dof], dof)
    # the ratings the CLI prints (three decimals)
    table = {line.split()[0]: line.split()[1:] for line in out.stdout.splitlines()[2:] if line.strip()}
    for dof, r in p.ratings().items():
        assert set(r) == {"r2", "pearson_r2", "rmse", "rmse_over_peak"}
        assert table[dof][0] == f"{r['r2']:.3f}", dof
        assert table[dof][1] == f"{r['pearson_r2']:.3f}", dof
    assert p.trial == TRIAL.name and p.model == "hill"


def test_a_prediction_survives_pickle_and_a_tampered_state_is_refused(subject):
    p = ma.predict(subject, MAP, TRIAL, model="hill", dofs=KNEE)
    q = pickle.loads(pickle.dumps(p))
    assert (q.trial, q.model, q.dofs, q.units) == (p.trial, p.model, p.dofs, p.units)
    assert (q.clamped_excitations, q.held_lengths) == (p.clamped_excitations, p.held_lengths)
    assert_bits_equal(q.time, p.time, "time")
    for field in ("force", "activation", "fibre_length"):
        assert_bits_equal(getattr(q, field).ravel(), getattr(p, field).ravel(), field)
    assert_bits_equal(q.moment[KNEE], p.moment[KNEE], KNEE)
    assert_bits_equal(q.measured[KNEE], p.measured[KNEE], KNEE)
    assert q.ratings() == p.ratings()
    # a state whose series disagree in length, or that is not one at all
    _, (state,) = p.__reduce__()
    meta, (times, *rest) = state
    with pytest.raises(ma.InputError, match="a sample per time"):
        ma.Prediction._from_state((meta, (times[:-1], *rest)))
    with pytest.raises(ma.InputError, match="layout"):
        ma.Prediction._from_state("not a state")
    # times that go back, a force that is not a number
    with pytest.raises(ma.InputError, match="times that rise"):
        ma.Prediction._from_state((meta, (list(reversed(times)), *rest)))
    units, force, *more = rest
    nan_force = [list(f) for f in force]
    nan_force[0][3] = float("nan")
    with pytest.raises(ma.InputError, match="finite values"):
        ma.Prediction._from_state((meta, (times, units, nan_force, *more)))


def test_predict_of_chosen_dofs_takes_their_units_only(cli, subject, tmp_path):
    p = ma.predict(SUBJECT, MAP, TRIAL, dofs=KNEE)
    assert p.dofs == [KNEE]
    assert set(p.units) == set(subject.dofs[KNEE])
    full = ma.predict(subject, MAP, TRIAL)
    # a unit's course does not depend on which others are driven beside it
    for i, u in enumerate(p.units):
        assert_bits_equal(p.force[i], full.force[full.units.index(u)], u)
    # the command line's --dofs: the same degrees of freedom and units, bit for bit
    moments_csv, muscles_csv = tmp_path / "moments.csv", tmp_path / "muscles.csv"
    cli("predict", "--subject", str(SUBJECT), "--excitations", str(MAP), "--trial", str(TRIAL),
        "--dofs", KNEE, "--csv", str(moments_csv), "--muscles-csv", str(muscles_csv))
    want_m, want_u = columns(moments_csv), columns(muscles_csv)
    assert list(want_m) == ["time", KNEE, f"{KNEE}_measured"]
    assert_bits_equal(p.moment[KNEE], want_m[KNEE], KNEE)
    assert [c[: -len(".force")] for c in want_u if c.endswith(".force")] == p.units
    for i, u in enumerate(p.units):
        assert_bits_equal(p.force[i], want_u[f"{u}.force"], u)


# --- (b) calibrate -------------------------------------------------------------------------


@pytest.fixture(scope="module")
def calibrated(subject):
    return ma.calibrate(subject, MAP, TWO_TRIALS, [KNEE], model="hill", seed=7, evaluations=30,
                        threads=2)


def test_calibrate_is_repeatable_for_a_seed_and_does_not_worsen(subject, calibrated):
    cal, result = calibrated
    again_cal, again = ma.calibrate(subject, MAP, TWO_TRIALS, KNEE, model="hill", seed=7,
                                    evaluations=30, threads=1)
    assert again == result and again_cal == cal          # on 1 thread as on 2
    assert again_cal.to_toml() == cal.to_toml()
    assert result["cost"] <= result["start_cost"]
    # Never more than asked: the whole generations of CMA-ES (13 candidates here) that fit.
    assert result["evaluations"] == 26 and [n for n, _ in result["history"]] == [13, 26]
    best = [c for _, c in result["history"]]
    assert best == sorted(best, reverse=True)
    # the result is the best found, re-driven, or the start when nothing beat it
    assert result["cost"] == pytest.approx(min(best[-1], result["start_cost"]), rel=1e-9)
    other_cal, other = ma.calibrate(subject, MAP, TWO_TRIALS, [KNEE], model="hill", seed=8,
                                    evaluations=30, threads=2)
    assert other["parameters"] != result["parameters"]   # the seed is used


def test_ctrl_c_stops_a_calibration_between_generations(subject):
    # interrupt_main is Ctrl-C. Run to its end, this calibration would take minutes and then
    # raise KeyboardInterrupt without the note that it stopped.
    # Python's own SIGINT handler, as a plain script has it: interrupt_main does nothing under
    # another one, which a library an earlier test loaded may have left.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as caught:
            ma.calibrate(subject, MAP, TWO_TRIALS, [KNEE], seed=7, evaluations=3000, threads=2)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    note = " ".join(getattr(caught.value, "__notes__", []))
    stopped = re.search(r"stopped after (\d+) of 3000 evaluations", note)
    assert stopped and 0 < int(stopped.group(1)) < 3000, note


def test_calibrate_gives_the_file_the_command_line_writes(cli, calibrated, tmp_path):
    out = tmp_path / "calibrated.toml"
    cli("calibrate", "--subject", str(SUBJECT), "--excitations", str(MAP),
        "--trials", *(str(t) for t in TWO_TRIALS), "--dofs", KNEE, "--model", "hill",
        "--out", str(out), "--seed", "7", "--evaluations", "30", "--threads", "2")
    cal, _ = calibrated
    assert out.read_text() == cal.to_toml()
    assert ma.Subject.read(out) == cal


def test_the_calibrated_subject_holds_the_result(subject, calibrated):
    cal, result = calibrated
    record = cal.calibration
    assert subject.calibration is None and record is not None
    assert record["seed"] == 7 and record["dofs"] == [KNEE] and record["model"] == "hill"
    assert record["trials"] == [t.name for t in TWO_TRIALS]
    assert record["cost"] == result["cost"] and record["parameters"] == result["parameters"]
    for unit in subject.dofs[KNEE]:
        params = cal.unit_params(unit)
        assert params["c1"] == result["parameters"]["c1"]
        assert params["shape_factor"] == result["parameters"]["shape_factor"]
    # and it predicts: a calibrated subject is a subject
    p = ma.predict(cal, MAP, TWO_TRIALS[0], dofs=[KNEE])
    assert np.isfinite(p.moment[KNEE]).all()


# --- (c) TOML and pickle ---------------------------------------------------------------------


def test_a_subject_survives_toml_a_file_and_pickle(cli, subject, tmp_path):
    text = subject.to_toml()
    back = ma.Subject.from_toml(text)
    assert back == subject and back.to_toml() == text
    assert back.id == subject.id and back.units == subject.units and back.dofs == subject.dofs
    for unit in subject.units:
        assert back.unit_params(unit) == subject.unit_params(unit)
    path = tmp_path / "subject.toml"
    path.write_text(text)
    assert ma.Subject.read(path) == subject
    assert pickle.loads(pickle.dumps(subject)) == subject
    # the command line's `subject` writes the same file
    cli("subject", str(SUBJECT), "--out", str(tmp_path / "cli.toml"))
    assert (tmp_path / "cli.toml").read_text() == text


def with_key(text: str, unit: str, key: str, value: float) -> str:
    """`text` with `key` of the [[muscle]] named `unit` set to `value` (as a user edits it)."""
    lines = text.splitlines()
    start = lines.index(f'name = "{unit}"')
    k = next(i for i in range(start, len(lines)) if lines[i].startswith(f"{key} = "))
    lines[k] = f"{key} = {value!r}"
    return "\n".join(lines) + "\n"


def test_a_subject_tells_its_units_and_parameters(subject):
    assert set(subject.dofs) >= {KNEE, "R_hip_fe", "R_ankle_fe"}
    assert all(set(u) <= set(subject.units) for u in subject.dofs.values())
    unit = subject.dofs[KNEE][0]
    p = subject.unit_params(unit)
    assert p["f_max"] > 0 and p["l_opt"] > 0 and p["curves"] == "tabulated"
    edited = ma.Subject.from_toml(with_key(subject.to_toml(), unit, "f_max", 2 * p["f_max"]))
    assert edited.unit_params(unit)["f_max"] == 2 * p["f_max"]
    assert edited != subject
    others = [u for u in subject.units if u != unit]
    assert all(edited.unit_params(u) == subject.unit_params(u) for u in others)
    assert subject.bounds["strength"] == [0.5, 2.5]
    assert "Subject(" in repr(subject)


def test_a_calibrated_subject_survives_toml(calibrated):
    cal, _ = calibrated
    assert ma.Subject.from_toml(cal.to_toml()) == cal
    assert pickle.loads(pickle.dumps(cal)) == cal


# --- (d) refusals ----------------------------------------------------------------------------


def one_line(e: pytest.ExceptionInfo) -> str:
    msg = str(e.value)
    assert msg and "\n" not in msg, msg
    return msg


def test_missing_files_raise_file_not_found(subject, tmp_path):
    with pytest.raises(ma.FileNotFound) as e:
        ma.Subject.read(tmp_path / "nobody.xml")
    assert isinstance(e.value, FileNotFoundError) and "nobody.xml" in one_line(e)
    with pytest.raises(ma.FileNotFound) as e:
        ma.predict(subject, tmp_path / "no-map.xml", TRIAL)
    assert "no-map.xml" in one_line(e)
    with pytest.raises(ma.FileNotFound) as e:
        ma.predict(subject, MAP, tmp_path / "no-trial")
    assert "no-trial" in one_line(e)
    with pytest.raises(ma.FileNotFound):
        ma.calibrate(subject, MAP, [TRIAL, tmp_path / "no-trial"], KNEE, evaluations=5)


def test_files_that_are_not_subjects_raise_config_error(tmp_path):
    for not_a_subject in (MAP, TRIAL / "emg.txt"):
        with pytest.raises(ma.ConfigError) as e:
            ma.Subject.read(not_a_subject)
        assert not_a_subject.name in one_line(e)
    with pytest.raises(ma.ConfigError) as e:
        ma.Subject.from_toml("x = 1\n")
    one_line(e)
    with pytest.raises(ma.ConfigError) as e:
        ma.Subject.from_toml('[subject]\nid = "s"\n')
    assert "muscle" in one_line(e)
    with pytest.raises(ma.ConfigError):                    # the subject file as the map
        ma.predict(SUBJECT, SUBJECT, TRIAL)
    with pytest.raises(ma.InputError):
        ma.predict(42, MAP, TRIAL)


def test_unknown_models_dofs_and_units_raise_unknown_name(subject):
    with pytest.raises(ma.UnknownNameError) as e:
        ma.predict(subject, MAP, TRIAL, model="hux")
    assert isinstance(e.value, KeyError) and "hux" in one_line(e)
    with pytest.raises(ma.UnknownNameError):
        ma.calibrate(subject, MAP, TWO_TRIALS, KNEE, model="hux", evaluations=5)
    with pytest.raises(ma.UnknownNameError) as e:
        ma.predict(subject, MAP, TRIAL, dofs=["L_elbow_fe"])
    assert "L_elbow_fe" in one_line(e)
    with pytest.raises(ma.UnknownNameError) as e:
        ma.calibrate(subject, MAP, TWO_TRIALS, ["R_knee_ab"], evaluations=5)
    assert "R_knee_ab" in one_line(e)
    with pytest.raises(ma.UnknownNameError) as e:
        subject.unit_params("biceps")
    assert "biceps" in one_line(e)


def test_bad_calibration_settings_raise_config_or_input_error(subject):
    for kwargs in ({"evaluations": 0}, {"threads": 0}, {"seed": -1}, {"evaluations": 10**7}):
        with pytest.raises(ma.ConfigError) as e:
            ma.calibrate(subject, MAP, TWO_TRIALS, KNEE, **kwargs)
        one_line(e)
    for dofs in ([], [KNEE, KNEE], [""]):
        with pytest.raises(ma.InputError):
            ma.calibrate(subject, MAP, TWO_TRIALS, dofs, evaluations=5)
    with pytest.raises(ma.InputError):
        ma.calibrate(subject, MAP, [], KNEE, evaluations=5)
    with pytest.raises(ma.InputError, match="given twice"):
        ma.calibrate(subject, MAP, [TRIAL, TRIAL], KNEE, evaluations=5)


def test_bad_emg_arguments_raise_typed_errors():
    x = np.random.default_rng(0).normal(size=2000)
    with pytest.raises(ma.ConfigError):
        ma.emg_envelope(x, 0.0)
    with pytest.raises(ma.ConfigError):
        ma.emg_envelope(x, 800.0)                            # 450 Hz is above Nyquist
    with pytest.raises(ma.ConfigError):
        ma.emg_envelope(x, 2000.0, low_pass_order=0)
    with pytest.raises(ma.UnknownNameError):
        ma.emg_envelope(x, 2000.0, phase="acausal")
    with pytest.raises(ma.UnknownNameError):
        ma.emg_envelope(x, 2000.0, normalisation="mvc")
    with pytest.raises(ma.InputError):
        ma.emg_envelope(np.where(np.arange(2000) == 7, np.nan, x), 2000.0)
    with pytest.raises(ma.InputError):
        ma.emg_envelope(np.zeros((2, 2, 10)), 2000.0)
    with pytest.raises(ma.InputError):
        ma.emg_envelope(np.zeros(2000), 2000.0)              # no peak to normalise by
    with pytest.raises(ma.ConfigError):
        ma.neural_activation(np.ones(10), 1.5, -0.5, 0.0)
    with pytest.raises(ma.ConfigError):
        ma.neural_activation(np.ones(10), -0.5, -0.5, 4.0)
    with pytest.raises(ma.ConfigError):
        ma.neural_activation(np.ones(10), -0.5, -0.5, 0.0, delay_samples=-1)


# --- (e) Ray ---------------------------------------------------------------------------------


def ray_example():
    spec = importlib.util.spec_from_file_location("ray_calibrate", ROOT / "examples" / "ray_calibrate.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["ray_calibrate"] = module
    spec.loader.exec_module(module)
    return module


def test_calibrations_on_ray_equal_the_local_loop(subject):
    if importlib.util.find_spec("ray") is None:
        pytest.skip("ray is not installed")
    example = ray_example()                                   # imports ray, as a script would
    ray = example.ray
    # The workers cannot import the example by name: its functions travel by value.
    ray.cloudpickle.register_pickle_by_value(example)
    sets = example.TRIAL_SETS[:2]
    ray.init(num_cpus=2, include_dashboard=False, _node_ip_address="127.0.0.1",
             log_to_driver=False, configure_logging=False)
    try:
        remote = example.on_ray(subject, sets, 5, 20)
    finally:
        ray.shutdown()
    local = example.locally(subject, sets, 5, 20)
    assert len(remote) == len(sets)
    for (rs, rr), (ls, lr) in zip(remote, local):
        assert rr == lr
        assert rs == ls and rs.to_toml() == ls.to_toml()
    assert remote[0][1] != remote[1][1]                       # different trials, different fits


# --- (f) EMG ---------------------------------------------------------------------------------


def test_emg_envelope_recovers_the_envelope_of_a_modulated_carrier():
    fs = 2000.0
    t = np.arange(0.0, 4.0, 1.0 / fs)
    envelope = 0.2 + 0.8 * np.sin(np.pi * t / 2.0) ** 2         # 0.5 Hz, well under 6 Hz
    raw = envelope * np.sin(2 * np.pi * 100.0 * t) + 0.3        # an amplifier offset too
    e = ma.emg_envelope(raw, fs)
    assert e.shape == raw.shape and abs(e.max() - 1.0) < 1e-12
    inner = slice(int(fs / 2), -int(fs / 2))                     # away from the ends
    r = np.corrcoef(e[inner], envelope[inner])[0, 1]
    assert r > 0.95, r
    # proportional to it: a rectified sine's mean is 2/π of its amplitude
    ratio = e[inner] / envelope[inner]
    assert ratio.std() / ratio.mean() < 0.05
    # several signals share one peak; the chain is linear but for rectification
    both = ma.emg_envelope(np.stack([raw, 0.5 * raw]), fs)
    np.testing.assert_allclose(both[0], e, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(both[1], 0.5 * e, rtol=1e-9, atol=1e-12)
    # an MVC peak or none instead of the signal's own
    plain = ma.emg_envelope(raw, fs, normalisation=None)
    np.testing.assert_allclose(ma.emg_envelope(raw, fs, normalisation=2.0), plain / 2.0, rtol=1e-12)
    # causal filters lag: the envelope's rise comes later
    causal = ma.emg_envelope(raw, fs, phase="causal")
    assert np.argmax(causal[: int(2.5 * fs)]) > np.argmax(e[: int(2.5 * fs)])


def test_emg_envelope_defaults_are_the_crates():
    defaults = ma._core._emg_envelope_defaults()
    signature = inspect.signature(ma.emg_envelope).parameters
    assert {k: signature[k].default for k in defaults} == defaults


def test_neural_activation_has_unit_steady_state_gain_and_its_delay():
    for level in (0.05, 0.3, 1.0):
        a = ma.neural_activation(np.full(3000, level), -0.6, -0.4, 0.0)
        assert abs(a[-1] - level) < 1e-12, level
        assert a[0] < level                                      # from rest
    # with a shape factor, the steady state is the nonlinearity of the excitation
    A = -2.0
    a = ma.neural_activation(np.full(3000, 0.3), -0.6, -0.4, A)
    assert abs(a[-1] - np.expm1(A * 0.3) / np.expm1(A)) < 1e-12
    assert abs(ma.neural_activation(np.ones(3000), -0.6, -0.4, A)[-1] - 1.0) < 1e-12
    # a step at sample 100 felt from sample 100 + delay
    e = np.where(np.arange(400) >= 100, 0.5, 0.0)
    d = ma.neural_activation(e, -0.6, -0.4, 0.0, delay_samples=20)
    assert (d[:120] == 0).all() and d[120] > 0
    np.testing.assert_array_equal(d[20:], ma.neural_activation(e, -0.6, -0.4, 0.0)[:-20])
    # rows are independent signals
    rows = ma.neural_activation(np.stack([e, 2 * e]), -0.6, -0.4, -1.0)
    np.testing.assert_array_equal(rows[1], ma.neural_activation(2 * e, -0.6, -0.4, -1.0))
