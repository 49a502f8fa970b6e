"""Contact-point methods and fit ranges from Python: the keywords reach the library (the same
numbers as the CLI's JSON report), the summary carries the point, and bad values are named."""
import json
import subprocess

import numpy as np
import pytest

import layerjkr

SCENE = {"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space", "E": 1e3, "nu": 0.5}}
E_TRUE, R, NU = 2e3, 5e-6, 0.5


def hertz_curve(n=600, dc=1e-7, noise=0.005, seed=3):
    delta = np.linspace(-1e-6, 1e-6, n)
    t = np.clip(delta - dc, 0.0, None)
    P = 4.0 / 3.0 * E_TRUE / (1 - NU ** 2) * np.sqrt(R) * t ** 1.5
    return delta, P + noise * P.max() * np.random.default_rng(seed).standard_normal(n)


@pytest.mark.parametrize("method", ["threshold", "rov", "gof"])
def test_each_method_fixes_the_contact_point_near_the_truth(method):
    delta, P = hertz_curve()
    r = layerjkr.fit(delta, P, SCENE, free="E", contact_point=method)
    c = r.contact_point
    assert c["method"] == method
    assert abs(c["value"] - 1e-7) < 4 * c["stderr"]
    assert c["samples_in_range"] == c["approach_samples"] == 600
    assert "contact point (%s)" % method in r.report()
    assert r.as_dict()["contact_point"]["method"] == method


def test_gof_with_a_range_matches_the_cli(cli, source, tmp_path):
    delta, P = hertz_curve()
    curve = tmp_path / "curve.csv"
    np.savetxt(curve, np.c_[delta, P, np.zeros(len(delta), int)], delimiter=",", header="delta,P,segment",
               comments="", fmt=["%.17g", "%.17g", "%d"])
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(SCENE))
    out = tmp_path / "fit.json"
    r = subprocess.run([cli, "fit", str(curve), "--scene", str(scene), "--free", "E,delta0", "--contact-point", "gof",
                        "--indentation-range", "-1e-7:4e-7", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    report = json.loads(out.read_text())
    py = layerjkr.fit(delta, P, SCENE, free="E,delta0", segment=np.zeros(len(delta), int), contact_point="gof",
                      indentation_range=(-1e-7, 4e-7))
    assert py.values["E"] == report["parameters"]["E"]["value"]
    assert py.contact_point["value"] == report["contact_point"]["value"]
    assert py.contact_point["samples_in_range"] == report["contact_point"]["samples_in_range"]
    kept = np.count_nonzero((delta >= py.contact_point["value"] - 1e-7) & (delta <= py.contact_point["value"] + 4e-7))
    assert py.contact_point["samples_in_range"] == kept
    assert abs(py.values["E"] - E_TRUE) < 4 * py.errors["E"]


def test_fit_batch_and_the_fitted_delta0():
    delta, P = hertz_curve()
    items = layerjkr.fit_batch([(delta, P)] * 2, SCENE, free="E,delta0", force_range=(0.0, 0.6))
    c = items[0].result.contact_point
    assert c["method"] == "fit"
    assert c["value"] == items[0].result.values["delta0"]
    assert c["stderr"] == items[0].result.errors["delta0"]
    assert 0 < c["samples_in_range"] < c["approach_samples"]
    plain = layerjkr.fit(delta, P, SCENE, free="E,delta0")
    assert np.isnan(plain.contact_point["range_reference"])


@pytest.mark.parametrize("kwargs, message", [
    ({"contact_point": "poc"}, "contact_point = \"poc\" is unknown (known: fit, threshold, rov, gof)"),
    ({"indentation_range": (1e-7, -1e-7)}, "indentation_range"),
    ({"indentation_range": 1e-7}, "indentation_range = 1e-07 is invalid"),
    ({"force_range": (0.0, 2.0)}, "force_range"),
    ({"baseline_window": (0.0, float("nan"))}, "baseline_window"),
])
def test_bad_values_are_named(kwargs, message):
    delta, P = hertz_curve()
    with pytest.raises(layerjkr.Error, match=None) as e:
        layerjkr.fit(delta, P, SCENE, free="E", **kwargs)
    assert message in str(e.value)


def test_a_retract_fit_refuses_a_method():
    delta, P = hertz_curve()
    with pytest.raises(layerjkr.InputError, match="contact point 'rov' needs approach samples"):
        layerjkr.fit(delta, P, SCENE, free="E", branch="retract", contact_point="rov")
