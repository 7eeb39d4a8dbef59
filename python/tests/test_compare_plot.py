"""`compare(a, b, plot=...)`: the overlay of the two runs' forces drawn by the package
(matplotlib), with the command line's refusal of a plot that would overwrite an input."""

from __future__ import annotations

import pytest

import muscle_actuator as ma


def test_the_plot_shows_each_muscles_force_of_both_runs(tmp_path):
    pytest.importorskip("matplotlib")
    from matplotlib.image import imread

    a, b = tmp_path / "hill.mcap", tmp_path / "dm.mcap"
    ma.simulate("pulse", model="hill", out=a)
    ma.simulate("pulse", model="huxley", out=b)
    got = ma.compare(a, b, plot=tmp_path / "cmp.png")
    assert got == ma.compare(a, b)
    png, svg = tmp_path / "cmp.png", tmp_path / "cmp.svg"
    assert imread(png).shape[:2] == (500, 800)
    text = svg.read_text()
    for label in ("flexor (hill)", "flexor (huxley)"):
        assert label in text
    assert "Tendon force: hill (solid) vs huxley (dashed)" in text


def test_a_plot_over_an_input_is_refused_and_the_input_kept(tmp_path):
    a, b = tmp_path / "a.mcap", tmp_path / "b.png"
    ma.simulate("pulse", model="hill", out=a)
    b_bytes = a.read_bytes()
    b.write_bytes(b_bytes)
    with pytest.raises(ma.InputError, match="would overwrite"):
        ma.compare(a, b, plot=tmp_path / "b.svg")
    assert b.read_bytes() == b_bytes
