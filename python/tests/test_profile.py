"""Profile intervals (#43): FitResult.profile(name) holds the parameter, refits the others and
finds where chi-square has risen by sigmas^2 reduced chi-squares - lmfit's conf_interval,
iminuit's minos. Oracle: a fit linear in its parameters, where the profile interval is the
symmetric error bar exactly."""
import pickle

import numpy as np
import pytest

import layerjkr

HERTZ = {"indenter": {"shape": "paraboloid", "R": 1e-5}, "medium": {"type": "half_space", "E": 2e4, "nu": 0.5},
         "w": 0.0}


# The fits' ModelWarnings are part of what they report, not of what these tests check.
pytestmark = pytest.mark.usefixtures("quiet")


def curve(spec, noise, seed=3):
    sim = layerjkr.simulate(layerjkr.scene(spec), max_indentation=1e-6, noise=noise, seed=seed)
    return sim.delta, sim.P, sim.segment


def test_a_linear_fit_has_the_error_bar_as_its_profile_interval():
    # With the contact point found beforehand the force is linear in E and P0: chi-square is
    # exactly quadratic, and the interval where it rises by one reduced chi-square is +- 1 SE.
    delta, P, segment = curve(HERTZ, 2e-11)
    r = layerjkr.fit(delta, P, HERTZ, free="E,P0", segment=segment, contact_point="threshold")
    for sigmas in (1.0, 2.0):
        p = r.profile("E", sigmas=sigmas)
        assert p.value == r.values["E"] and p.standard_error == r.errors["E"]
        assert p.lower == pytest.approx(p.value - sigmas * p.standard_error, abs=3e-3 * p.standard_error)
        assert p.upper == pytest.approx(p.value + sigmas * p.standard_error, abs=3e-3 * p.standard_error)
        assert not p.lower_at_domain_edge and not p.upper_at_domain_edge and p.fits > 4


def test_an_end_at_the_domain_is_flagged():
    # Almost no adhesion beside the noise: w's interval runs into w = 0, which the scene refuses.
    spec = dict(HERTZ, w=1e-7)
    delta, P, segment = curve(spec, 5e-10)
    r = layerjkr.fit(delta, P, spec, free="E,w,delta0,P0", segment=segment, branch="all")
    p = r.profile("w", sigmas=2.0)
    assert p.lower_at_domain_edge and 0.0 <= p.lower < p.value + 1e-12 and p.upper > p.value
    assert not p.upper_at_domain_edge


def test_what_cannot_be_profiled_is_refused():
    delta, P, segment = curve(HERTZ, 2e-11)
    r = layerjkr.fit(delta, P, HERTZ, free="E,delta0,P0", segment=segment)
    for name, says in (("delta0", "belongs to the data"), ("w", "not a free parameter")):
        with pytest.raises(layerjkr.InputError, match=says):
            r.profile(name)
    with pytest.raises(layerjkr.InputError, match="sigmas"):
        r.profile("E", sigmas=0.0)
    with pytest.raises(layerjkr.InputError, match="cannot be refitted"):
        pickle.loads(pickle.dumps(r)).profile("E")
    batch = layerjkr.fit_batch([(delta, P)], HERTZ, free="E,delta0,P0")
    with pytest.raises(layerjkr.InputError, match="cannot be refitted"):
        batch[0].result.profile("E")
