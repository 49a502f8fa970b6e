"""Bad input from Python (issue #21): segment labels refused by value, wrong option types a
TypeError naming the parameter, empty radii an InputError, numpy values in scene dicts, and
the scene reader's limits (deep nesting killed the interpreter)."""
import json

import numpy as np
import pytest

import layerjkr

SCENE = "data/scenes/hydrogel_film_two_term.json"
CURVE = "data/curves/hydrogel_film_two_term.csv"

pytestmark = pytest.mark.filterwarnings("ignore::layerjkr.ModelWarning")


def curve_arrays(source):
    rows = [l.split(",") for l in (source / CURVE).read_text().splitlines() if l and l[0] not in "#d"]
    d, P, seg = (np.array([float(r[k]) for r in rows]) for k in range(3))
    return d, P, seg


def test_non_integer_segment_labels_are_refused_with_the_value(source):
    d, P, seg = curve_arrays(source)
    with pytest.raises(layerjkr.InputError, match=r"segment\[0\] = 0.25 is not a segment label"):
        layerjkr.fit(d, P, str(source / SCENE), segment=seg * 0.5 + 0.25)
    with pytest.raises(layerjkr.InputError, match="segment"):
        layerjkr.fit(d, P, str(source / SCENE), segment=np.where(seg > 0, np.nan, 0.0))
    # Whole-valued floats are labels.
    r = layerjkr.fit(d, P, str(source / SCENE), segment=seg.astype(np.float64))
    assert np.isfinite(r.values["E"])


@pytest.mark.parametrize("option, value", [
    ("starts", "3"), ("max_iterations", 2.5), ("window_fraction", "x"), ("spring_constant", "x"),
    ("branch", 3), ("loss", None), ("free", ["E", 3]), ("loss_scale", [1.0])])
def test_wrong_option_types_are_type_errors_naming_the_parameter(source, option, value):
    d, P, _ = curve_arrays(source)
    with pytest.raises(TypeError, match=option):
        layerjkr.fit(d, P, str(source / SCENE), **{option: value})


def test_wrong_types_elsewhere_name_the_parameter(source):
    with pytest.raises(TypeError, match="warning_threshold"):
        layerjkr.summary(str(source / SCENE), warning_threshold="x")
    with pytest.raises(TypeError, match="units"):
        layerjkr.fit_files(str(source / CURVE), str(source / SCENE), units=3)
    with pytest.raises(TypeError, match="jobs"):
        layerjkr.fit_files(str(source / CURVE), str(source / SCENE), jobs="2")


def test_empty_radii_are_an_input_error(source):
    for empty in (np.array([]), [], np.empty(0, dtype=np.float32)):
        with pytest.raises(layerjkr.InputError, match="at least one contact radius"):
            layerjkr.curve(str(source / SCENE), empty)


def test_numpy_values_in_a_scene_dict(source):
    spec = json.loads((source / SCENE).read_text())
    plain = layerjkr.summary(spec)
    spec["w"] = np.float64(spec["w"])
    spec["indenter"]["R"] = np.float32(spec["indenter"]["R"])
    spec["medium"]["E"] = np.int64(spec["medium"]["E"])
    s = layerjkr.summary(spec)
    assert s.pull_off_force == pytest.approx(plain.pull_off_force, rel=1e-6)  # R through float32
    r = np.linspace(0.0, 5e-6, 41)
    table = {"indenter": {"shape": "table", "r": r, "z": r ** 2 / 2e-5}, "medium": spec["medium"],
             "model": "two_term", "w": 0.001}
    assert np.isfinite(layerjkr.summary(table).pull_off_force)


def test_deep_nesting_and_repeated_keys_are_input_errors():
    with pytest.raises(layerjkr.InputError, match="deeper than 32 levels"):
        layerjkr._core.parse_scene("[" * 100000 + "]" * 100000, "deep")
    with pytest.raises(layerjkr.InputError, match="model is given twice"):
        layerjkr._core.parse_scene('{"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "winkler", '
                                   '"K": 1e9}, "model": "winkler", "model": "winkler"}', "dup")
