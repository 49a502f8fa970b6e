"""fit(start=, fixed=) (#43): starting and fixed values as arguments, as lmfit and iminuit users
give them, equal to editing the scene - and refused by name where they cannot apply."""
import warnings

import numpy as np
import pytest

import layerjkr

TRUTH = {"indenter": {"shape": "paraboloid", "R": 1e-5}, "medium": {"type": "half_space", "E": 2e4, "nu": 0.5},
         "w": 1e-4}


def scene_with(E, w):
    spec = {**TRUTH, "medium": {**TRUTH["medium"], "E": E}, "w": w}
    return layerjkr.scene(spec)


@pytest.fixture(scope="module")
def curve():
    sim = layerjkr.simulate(layerjkr.scene(TRUTH), max_indentation=1e-6, noise=1e-11, seed=3)
    return sim.delta, sim.P, sim.segment


def fit(curve, scene, **kw):
    delta, P, segment = curve
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return layerjkr.fit(delta, P, scene, segment=segment, branch="all", **kw)


def test_start_is_the_scene_with_those_values(curve):
    # A scene 10x off, started from given values, fits as the scene holding those values does.
    given = fit(curve, scene_with(2e5, 1e-3), free="E,w,delta0,P0", start={"E": 3e4, "w": 2e-4})
    edited = fit(curve, scene_with(3e4, 2e-4), free="E,w,delta0,P0")
    assert np.array_equal(given.values, edited.values)
    assert given.values["E"] == pytest.approx(2e4, rel=0.01)
    assert given.provenance["scene"]["json"]["medium"]["E"] == 3e4  # the record says what was fitted


def test_fixed_holds_a_value_the_scene_had_otherwise(curve):
    held = fit(curve, scene_with(2e4, 1e-4), free="E,delta0,P0", fixed={"w": 2e-4})
    edited = fit(curve, scene_with(2e4, 2e-4), free="E,delta0,P0")
    assert np.array_equal(held.values, edited.values)
    assert held.values["E"] != pytest.approx(2e4, rel=1e-3)  # w held wrong moves E: the value was used


@pytest.mark.parametrize("kw, says", [
    ({"start": {"R": 1e-5}}, "start['R']: not in free"),
    ({"fixed": {"E": 1e4}}, "fixed['E']: is free"),
    ({"fixed": {"P0": 0.0}}, "fixed['P0']: is free"),
    ({"start": [1, 2]}, "start = [1, 2] is invalid"),
    ({"fixed": {"w": float("nan")}}, "fixed['w'] = nan is invalid"),
    ({"fixed": {"zz": 1.0}}, "fit(start=, fixed=): "),
    ({"fixed": {"w": -1.0}}, "fit(start=, fixed=): "),
])
def test_refused_by_name(curve, kw, says):
    with pytest.raises(layerjkr.InputError) as e:
        fit(curve, scene_with(2e4, 1e-4), free="E,delta0,P0", **kw)
    assert says in str(e.value)


def test_offsets_belong_to_the_data(curve):
    with pytest.raises(layerjkr.InputError, match="delta0 and P0 belong to the data"):
        fit(curve, scene_with(2e4, 1e-4), free="E,w", fixed={"delta0": 0.0})


def test_bounds_hold_a_parameter_in_its_range(curve):
    free = fit(curve, scene_with(2e4, 1e-4), free="E,w,delta0,P0")
    loose = fit(curve, scene_with(2e4, 1e-4), free="E,w,delta0,P0", bounds={"E": (1e3, None), "w": (0, 1)})
    assert loose.values["E"] == pytest.approx(free.values["E"], rel=1e-6)
    with pytest.warns(layerjkr.ModelWarning, match="at the end of its range"):
        delta, P, segment = curve
        tight = layerjkr.fit(delta, P, scene_with(2e4, 1e-4), segment=segment, branch="all", free="E,w,delta0,P0",
                             bounds={"E": (None, 1.5e4)})
    assert tight.values["E"] == pytest.approx(1.5e4, rel=1e-9) and np.isnan(tight.errors["E"])
    assert tight.as_dict()["parameters"]["E"]["at_bound"] is True
    # The profile of a bounded parameter refits the others inside their own ranges.
    p = loose.profile("w")
    assert p.lower < loose.values["w"] < p.upper


@pytest.mark.parametrize("bounds, says", [
    ({"R": (1e-6, 1e-5)}, "bounds of R: the parameter is not free"),
    ({"E": (2e4, 1e4)}, "bounds of E"),
    ({"E": 5}, r"bounds\['E'\] = 5 is invalid"),
    ([("E", 1, 2)], "bounds = .* is invalid"),
    ({"Q": (1, 2)}, "is unknown"),
])
def test_bounds_refused_by_name(curve, bounds, says):
    with pytest.raises((layerjkr.InputError, layerjkr.DomainError), match=says):
        fit(curve, scene_with(2e4, 1e-4), free="E,w,delta0,P0", bounds=bounds)
