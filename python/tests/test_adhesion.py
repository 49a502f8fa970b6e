"""Adhesion models from Python: the scene's "adhesion" key, the summary's adhesion check and
the curve's adhesive-zone radius c, against the CLI and Maugis' closed form."""
import json
import math
import subprocess

import numpy as np
import pytest

import layerjkr

TIP = {"shape": "paraboloid", "R": 2e-8}
POLYMER = {"type": "half_space", "E": 3e9, "nu": 0.4}


def test_jkr_on_a_stiff_polymer_warns_with_lambda_and_the_error():
    with pytest.warns(layerjkr.ModelWarning, match=r"JKR is outside its range here: lambda = 0\.608"):
        s = layerjkr.summary({"indenter": TIP, "medium": POLYMER, "w": 0.05})
    assert s.adhesion_model == "jkr"
    c = s.adhesion
    assert isinstance(c, layerjkr.AdhesionCheck)
    assert c.sigma0_assumed and c.basis == "closed form"
    assert c.sigma0 == pytest.approx(16 * 0.05 / (9 * math.sqrt(3) * 0.3e-9), rel=1e-12)
    assert 0.10 < c.pull_off_error < 0.12
    assert s["adhesion_check"]["lambda"] == c.lambda_


def test_maugis_dugdale_summary_and_curve_equal_the_cli(cli, source, tmp_path):
    spec = {"indenter": TIP, "medium": POLYMER, "w": 0.05, "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}}
    path = tmp_path / "md.json"
    path.write_text(json.dumps(spec))
    s = layerjkr.summary(spec)
    ref = json.loads(subprocess.run([cli, "summary", str(path)], capture_output=True, text=True, check=True).stdout)
    assert s.as_dict() == ref
    assert s.adhesion_model == "maugis_dugdale" and s.adhesion.pull_off_error == 0.0
    # Between JKR's -3/2 pi w R and DMT's -2 pi w R.
    assert -2.0 * math.pi * 0.05 * 2e-8 < s.pull_off_force < -1.5 * math.pi * 0.05 * 2e-8
    a = np.array([1e-9, 3e-9, 6e-9])
    curve = layerjkr.curve(spec, a)
    assert np.all(curve.c > curve.a) and np.all(np.isfinite(curve.P_H))
    rows = subprocess.run([cli, "curve", str(path), "--at", "1e-9,3e-9,6e-9"], capture_output=True, text=True,
                          check=True).stdout.splitlines()
    assert rows[0].endswith(",c")
    assert [float(r.split(",")[-1]) for r in rows[1:]] == list(curve["c"])


def test_a_bad_adhesion_key_is_an_input_error():
    with pytest.raises(layerjkr.InputError, match=r"adhesion\.sigma0"):
        layerjkr.summary({"indenter": TIP, "medium": POLYMER, "w": 0.05,
                          "adhesion": {"model": "maugis_dugdale", "sigma0": -1.0}})
