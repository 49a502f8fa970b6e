"""Fits and curves in time from Python: simulate -> fit round trips for a relaxing layer, a joint
fit across speeds, the rate-dependent pull-off of a summary (the CLI's numbers), and bad input."""
import json
import subprocess

import numpy as np
import pytest

import layerjkr

CELL = {"indenter": {"shape": "paraboloid", "R": 5e-6},
        "medium": {"type": "layer", "E": 2000, "nu": 0.49, "h": 3e-6, "base": "bonded",
                   "viscoelastic": {"law": "sls", "E_inf": 800, "tau": 0.2}}, "model": "exact"}
GUESS = {**CELL, "medium": {**CELL["medium"], "E": 5000, "viscoelastic": {"law": "sls", "E_inf": 320, "tau": 0.5}}}
ELASTOMER = {"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6, "nu": 0.5},
             "w": 0.05, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}}


def test_simulate_then_fit_in_time():
    s = layerjkr.simulate(CELL, max_indentation=2e-6, speed=2e-6, dwell=0.3, points=200, noise=5e-11, seed=4,
                          with_radius=True)
    assert s.t.dtype == np.float64 and np.all(np.diff(s.t) > 0)
    assert set(np.unique(s.segment)) == {0, 1, 2}
    assert s.a.shape == s.P.shape
    r = layerjkr.fit(s.delta, s.P, GUESS, free="E,E_inf,tau,delta0", t=s.t, segment=s.segment, branch="all")
    assert r.family == "hereditary"
    for name, truth in (("E", 2000.0), ("E_inf", 800.0), ("tau", 0.2)):
        assert abs(r.values[name] - truth) < 3 * r.errors[name], name
    assert r.t.shape == r.P.shape
    assert r.as_dict()["parameters"]["tau"]["unit"] == "s"


def test_fit_joint_across_speeds():
    curves = [layerjkr.simulate(CELL, max_indentation=2e-6, speed=v, points=150, noise=5e-11, seed=k)
              for k, v in enumerate((0.5e-6, 2e-6, 8e-6))]
    j = layerjkr.fit_joint(curves, GUESS, free=["E", "E_inf", "tau", "delta0"])
    # Curves count from 0, as curves[k], alone[k] and curve_begin[k] do (issue 43).
    assert j.fit.parameters == ("E", "E_inf", "tau", "delta0[0]", "delta0[1]", "delta0[2]")
    assert [s["path"] for s in j.fit.provenance["inputs"]][:2] == ["curves[0] delta (float64 array)",
                                                                    "curves[0] P (float64 array)"]
    assert abs(j.fit.values["tau"] - 0.2) < 3 * j.fit.errors["tau"]
    assert list(j.curve_begin) == [0, 300, 600, 900]
    assert len(j.alone) == 3 and all(a.errors["E"] > j.fit.errors["E"] for a in j.alone)
    # Tuples and dicts as well as simulations.
    j2 = layerjkr.fit_joint([(c.delta, c.P, c.segment, c.t) for c in curves[:2]] +
                            [{"delta": curves[2].delta, "P": curves[2].P, "t": curves[2].t}], GUESS,
                            free="E,E_inf,tau,delta0")
    assert j2.fit.values["tau"] == pytest.approx(j.fit.values["tau"], rel=1e-3)
    # The same measurement twice would shrink every error bar by sqrt(2) (issue 41): refused.
    with pytest.raises(layerjkr.InputError, match=r"fit_joint: curves\[0\] and curves\[2\] hold the same samples"):
        layerjkr.fit_joint([curves[0], curves[1], curves[0]], GUESS, free=["E", "E_inf", "tau", "delta0"])
    # A curve that cannot be fitted is named as the caller wrote it.
    late = (curves[1].delta + 1e-5, curves[1].P, curves[1].segment, curves[1].t)
    with pytest.raises(layerjkr.InputError, match=r"fit_joint: curves\[1\] cannot be fitted alone"):
        layerjkr.fit_joint([curves[0], late], GUESS, free=["E", "E_inf", "tau"])


def test_summary_rate_dependent_pull_off_is_the_clis(cli, tmp_path):
    path = tmp_path / "elastomer.json"
    path.write_text(json.dumps(ELASTOMER))
    s = layerjkr.summary(ELASTOMER, retract_speed=1e-6)
    out = subprocess.run([cli, "summary", str(path), "--retract-speed", "1e-6"], capture_output=True, text=True, check=True)
    assert s.as_dict()["kinetic_pull_off"] == json.loads(out.stdout)["kinetic_pull_off"]
    assert s.kinetic["pull_off_force"] < s.pull_off_force
    assert layerjkr.summary(ELASTOMER).kinetic is None


def test_time_bad_input():
    with pytest.raises(layerjkr.InputError, match="give the indenter's speed"):
        layerjkr.simulate(CELL, max_indentation=2e-6)
    with pytest.raises(layerjkr.DomainError, match="dwell"):
        layerjkr.simulate(CELL, max_indentation=2e-6, dwell=1.0)
    with pytest.raises(layerjkr.InputError, match="branch"):
        layerjkr.simulate(CELL, max_indentation=2e-6, speed=1e-6, branch="sideways")
    with pytest.raises(layerjkr.InputError, match="retract_speed or load_rate"):
        layerjkr.summary(ELASTOMER, retract_speed=1e-6, load_rate=1.0)
    with pytest.raises(layerjkr.InputError, match="not a curve"):
        layerjkr.fit_joint([1, 2], CELL)
    with pytest.raises(layerjkr.InputError, match="at least 2 curves"):
        layerjkr.fit_joint([layerjkr.simulate(CELL, max_indentation=2e-6, speed=1e-6, points=50)], CELL)
    s = layerjkr.simulate(CELL, max_indentation=2e-6, speed=1e-6, points=50)
    with pytest.raises(layerjkr.InputError, match=r"has no time: .*Python's fit\(\.\.\., t=\)"):  # in Python's terms too
        layerjkr.fit(s.delta, s.P, CELL, free="E", segment=s.segment)
    with pytest.raises(layerjkr.InputError, match="segment"):
        layerjkr.fit(s.delta, s.P, CELL, free="E", segment=np.full(len(s.P), 3), t=s.t)


def test_docs_in_time_example_runs():
    """docs/python.md's "In time" block, run as written: the documented scenes parse and answer."""
    import pathlib
    text = (pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md").read_text()
    block = text[text.index("## In time"):].split("```python", 1)[1].split("```", 1)[0]
    names = {"layerjkr": layerjkr}
    exec(compile(block, "docs/python.md", "exec"), names)
    assert abs(names["r"].values["tau"] - 0.2) < 3 * names["r"].errors["tau"]
    assert names["j"].fit.parameters[:3] == ("E", "E_inf", "tau")


def test_the_levers_drag_from_python():
    # Issue 42: simulate(drag=) adds b v; fit(free="...,drag") finds it within its error bar.
    truth = {"indenter": {"shape": "paraboloid", "R": 5e-6},
             "medium": {"type": "half_space", "E": 2000, "nu": 0.49,
                        "viscoelastic": {"law": "power_law", "beta": 0.2, "t0": 1}}}
    s = layerjkr.simulate(truth, max_indentation=1e-6, speed=5e-6, points=200, noise=5e-12, drag=5e-5, seed=2)
    r = layerjkr.fit(s.delta, s.P, truth, segment=s.segment, t=s.t, free="E,beta,drag,delta0,P0", branch="all")
    assert abs(r.values["drag"] - 5e-5) < 3 * r.errors["drag"]
    assert r.parameters == ("E", "beta", "drag", "delta0", "P0")
    with pytest.raises(layerjkr.InputError, match="needs a speed"):
        layerjkr.simulate(truth, max_indentation=1e-6, drag=1e-6)
