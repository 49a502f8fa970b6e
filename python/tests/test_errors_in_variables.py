"""fit(displacement_noise=): errors in both variables for a JKR rig whose displacement sensor has
noise of its own (the C++ oracles are in tests/fit/test_fit_errors_in_variables.cpp)."""
import math

import numpy as np
import pytest

import layerjkr

E, NU, W, R = 1e6, 0.49, 0.05, 5e-3
ES = E / (1 - NU ** 2)
SCENE = {"indenter": {"shape": "paraboloid", "R": R}, "medium": {"type": "half_space", "E": 2e6, "nu": NU}, "w": W}


def rig(seed: int) -> tuple:
    """The classical JKR sphere loaded from 1.2x its zero-load radius to 4x the pull-off radius and
    unloaded to 1.15x it, 150 samples each; noise in P (0.2 % of the pull-off) and delta (1 % of the span)."""
    a_po = (9 * math.pi * W * R ** 2 / (8 * ES)) ** (1 / 3)
    a = np.concatenate([np.linspace(1.2 * 4 ** (1 / 3) * a_po, 4 * a_po, 150), np.linspace(4 * a_po, 1.15 * a_po, 150)])
    delta = a ** 2 / R - np.sqrt(2 * math.pi * W * a / ES)
    P = 4 * ES * a ** 3 / (3 * R) - np.sqrt(8 * math.pi * W * ES * a ** 3)
    rng = np.random.default_rng(seed)
    sd, sP = 0.01 * (delta.max() - delta.min()), 0.002 * 1.5 * math.pi * W * R
    return delta + sd * rng.standard_normal(300), P + sP * rng.standard_normal(300), sd, sP


def test_fit_with_errors_in_both_variables(quiet):
    delta, P, sd, sP = rig(3)
    segment = np.repeat([0, 1], 150)
    r = layerjkr.fit(delta, P, SCENE, free="E,w,delta0", segment=segment, branch="all", displacement_noise="auto")
    noise = r.as_dict()["noise"]  # as the CLI's JSON report gives it
    assert noise["delta"] == pytest.approx(sd, rel=0.3) and not noise["delta_given"]
    assert noise["P"] == pytest.approx(sP, rel=0.3)
    assert abs(r.values["E"] - E) < 4 * r.errors["E"]
    given = layerjkr.fit(delta, P, SCENE, free="E,w,delta0", segment=segment, branch="all", displacement_noise=sd,
                         force_noise=sP)
    assert given.as_dict()["noise"]["delta_given"] and given.as_dict()["noise"]["P_given"]
    assert given.values["E"] == pytest.approx(r.values["E"], rel=0.02)
    assert given.provenance["options"]["errors_in_displacement"] is True


def test_displacement_noise_refused_by_name():
    delta, P, _, _ = rig(1)
    with pytest.raises(layerjkr.InputError, match="displacement_noise.*auto"):
        layerjkr.fit(delta, P, SCENE, free="E,w,delta0", branch="all", displacement_noise="estimate")
    with pytest.raises(layerjkr.InputError, match="displacement_noise = -1.0.*> 0"):
        layerjkr.fit(delta, P, SCENE, free="E,w,delta0", branch="all", displacement_noise=-1.0)
