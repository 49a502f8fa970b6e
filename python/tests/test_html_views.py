"""Notebook views (#43): Scene, Curve, Summary, Simulation, FitResult, joint fits and batches each
have a `_repr_html_` that summarises them - values with units, counts, warnings - escaped."""

import numpy as np
import pytest

import layerjkr

SPEC = {"indenter": {"shape": "paraboloid", "R": 1e-5}, "medium": {"type": "half_space", "E": 2e4, "nu": 0.5},
        "w": 1e-4}
CELL = {"indenter": {"shape": "paraboloid", "R": 5e-6},
        "medium": {"type": "half_space", "E": 2000.0, "nu": 0.5,
                   "viscoelastic": {"law": "sls", "E_inf": 800.0, "tau": 0.2}}, "w": 0.0}


# The fits' ModelWarnings are part of what they report, not of what these tests check.
pytestmark = pytest.mark.usefixtures("quiet")


def test_scene_shows_its_values():
    h = layerjkr.scene(SPEC)._repr_html_()
    assert h.startswith("<table>") and "<td>medium.E</td><td>20000</td>" in h and "<td>w</td><td>0.0001</td>" in h


def test_curve_shows_head_and_tail_and_its_warnings():
    c = layerjkr.curve(layerjkr.scene(SPEC), np.linspace(1e-7, 2e-6, 40))
    h = c._repr_html_()
    assert "40 radii" in h and h.count("<tr>") == 1 + 11  # header, 5 + "..." + 5 rows
    assert "%.6g" % c.P[0] in h and "%.6g" % c.P[-1] in h and "<td>...</td>" in h


def test_summary_shows_quantities_with_units():
    m = layerjkr.summary(layerjkr.scene(SPEC))
    h = m._repr_html_()
    assert "<td>pull-off force</td><td>%.6g</td><td>N</td>" % m.pull_off_force in h


def test_simulation_shows_segments_not_arrays():
    sim = layerjkr.simulate(layerjkr.scene(CELL), max_indentation=2e-6, speed=2e-6, dwell=0.1, points=100)
    h = sim._repr_html_()
    assert "<td>approach</td><td>100</td>" in h and "<td>dwell</td>" in h and len(h) < 3000


def test_fit_joint_and_batch_views():
    s = layerjkr.scene(SPEC)
    sim = layerjkr.simulate(s, max_indentation=1e-6, noise=1e-11, seed=2)
    r = layerjkr.fit(sim.delta, sim.P, s, segment=sim.segment, branch="all", free="E,w,delta0,P0")
    assert "<td>E</td><td>%.6g</td>" % r.values["E"] in r._repr_html_()
    runs = [layerjkr.simulate(layerjkr.scene(CELL), max_indentation=2e-6, speed=v, points=120, noise=5e-11, seed=k)
            for k, v in enumerate((1e-6, 4e-6))]
    j = layerjkr.fit_joint(runs, layerjkr.scene(CELL), free="E,E_inf,tau,delta0")
    h = j._repr_html_()
    assert "each curve fitted alone" in h and "<td>curves[0]</td>" in h and "<td>curves[1]</td>" in h
    batch = layerjkr.fit_batch([(sim.delta, sim.P), (sim.delta[:3], sim.P[:3])], s, free="E,w,delta0")
    h = batch._repr_html_()
    assert "2 curves, 1 fitted, 1 failed" in h and "<td>E</td><td>1</td>" in h


def test_views_escape_what_they_quote():
    # Every view goes through one table builder, which escapes captions, text cells and notes.
    from layerjkr._html import number, table
    h = table("a <b>", ("x<y",), [(number("<i>"),)], ["warning: a < b & c"])
    assert "<b>" not in h and "&lt;b&gt;" in h and "&lt;i&gt;" in h and "a &lt; b &amp; c" in h
    assert number(float("nan")) == "-" and number(None) == "-" and number(1.23456789) == "1.23457"
