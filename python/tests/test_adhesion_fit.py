"""Fits with the scene's adhesion model: free=["sigma0"] on a Maugis-Dugdale half-space, and
Maugis-Dugdale on a film (the "dugdale" family).

The curve is written here from Maugis' equations (Johnson & Greenwood 1997 notation), solved by
bisection in plain Python: an oracle that shares nothing with the library's solver.
"""
import math

import re
import warnings

import numpy as np
import pytest

import layerjkr

R, E, NU, W = 20e-9, 1e9, 0.3, 0.05
E_STAR = E / (1 - NU**2)
K = 4.0 * E_STAR / 3.0


def _s_of(lam, A):
    """s = sqrt(m^2 - 1): the root of Maugis' first equation, increasing in s."""
    def f(s):
        m = math.hypot(1.0, s)
        g1 = s + (s * s - 1.0) * math.atan(s)
        g2 = s * math.atan(s) - m + 1.0
        return 0.5 * lam * A * A * g1 + 4.0 / 3.0 * lam * lam * A * g2 - 1.0
    lo, hi = 0.0, 1.0
    while f(hi) < 0.0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


def _point(lam, A):
    s = _s_of(lam, A)
    m2 = 1.0 + s * s
    return A**3 - lam * A * A * (s + m2 * math.atan(s)), A * A - 4.0 / 3.0 * lam * A * s


def _maugis_retract(lam):
    """Retract from A_po + 4 to the load-controlled pull-off, then free samples at P = 0."""
    a, b = 1e-3, 3.0  # golden section for the minimum of P(A)
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(80):
        c, d = b - g * (b - a), a + g * (b - a)
        a, b = (a, d) if _point(lam, c)[0] < _point(lam, d)[0] else (c, b)
    A_po = 0.5 * (a + b)
    length = (math.pi * W * R * R / K) ** (1.0 / 3.0)
    A = np.linspace(A_po + 4.0, A_po, 200)
    pts = np.array([_point(lam, x) for x in A])
    P = pts[:, 0] * math.pi * W * R
    d = pts[:, 1] * length**2 / R
    free = np.linspace(d[-1], d[-1] - 0.5 * (d[0] - d[-1]), 101)[1:]
    return np.concatenate([d, free]), np.concatenate([P, np.zeros(free.size)])


def _scene(adhesion, E_scene=E):
    return {"indenter": {"shape": "paraboloid", "R": R}, "medium": {"type": "half_space", "E": E_scene, "nu": NU},
            "adhesion": adhesion}


def test_free_sigma0_recovers_a_maugis_dugdale_curve():
    lam = 1.0
    sigma0 = lam / (2.0 * (R / (math.pi * W * K * K)) ** (1.0 / 3.0))
    delta, P = _maugis_retract(lam)
    r = layerjkr.fit(delta, P, _scene({"model": "maugis_dugdale", "sigma0": 2.0 * sigma0}, 2.0 * E),
                     free=["E", "w", "sigma0"], segment=np.ones(delta.size, dtype=int), branch="retract")
    assert r.converged and r.identifiable
    assert abs(r.values["E"] / E - 1) < 1e-6
    assert abs(r.values["w"] / W - 1) < 1e-6
    assert abs(r.values["sigma0"] / sigma0 - 1) < 1e-6
    assert np.isfinite(r.errors["sigma0"]) and r.reasons["sigma0"] == ""
    assert r.model == "maugis_dugdale on half_space"


def test_free_sigma0_without_a_dugdale_law_is_refused():
    delta, P = _maugis_retract(1.0)
    with pytest.raises(layerjkr.InputError, match="sigma0.*'jkr'"):
        layerjkr.fit(delta, P, _scene({"model": "jkr"}), free=["E", "w", "sigma0"],
                     segment=np.ones(delta.size, dtype=int), branch="retract")


def test_maugis_dugdale_on_a_film_fits_back_the_library_curve():
    # The film's curve from layerjkr.curve (the Dugdale solver at each radius), fitted by the
    # dugdale family (a grid of radii per parameter vector, scaled in E): E and w to 1e-5.
    film = {"indenter": {"shape": "paraboloid", "R": R}, "medium": {"type": "layer", "E": 3e9, "nu": NU, "h": 1e-8},
            "model": "exact", "w": W, "adhesion": {"model": "maugis_dugdale", "sigma0": 1.7e8}}
    a = np.linspace(17e-9, 1.9e-9, 40)  # down to just above the pull-off radius (1.866 nm)
    c = layerjkr.curve(film, a)
    span = c.delta[0] - c.delta[-1]
    delta = np.concatenate([c.delta, c.delta[-1] - span * np.arange(1, 21) / 40])
    P = np.concatenate([c.P, np.zeros(20)])
    start = dict(film, medium=dict(film["medium"], E=6e9))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # its ~1e-8 interpolation error is a notice, not a warning
        r = layerjkr.fit(delta, P, start, free=["E", "w"], segment=np.ones(delta.size, dtype=int), branch="retract")
    assert any(re.search("31 radii .* interpolation error", n) for n in r.notices)
    assert r.converged
    assert r.family == "dugdale" and r.model == "maugis_dugdale on exact"
    assert abs(r.values["E"] / 3e9 - 1) < 1e-5
    assert abs(r.values["w"] / W - 1) < 1e-5
