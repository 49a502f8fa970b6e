"""Bad input from Python (issue #21): segment labels refused by value, wrong option types a
TypeError naming the parameter, empty radii an InputError, numpy values in scene dicts, and
the scene reader's limits (deep nesting killed the interpreter)."""
import json
import os

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


def test_fit_files_takes_any_file_name_and_gives_it_back_as_os_fsdecode_does(source, tmp_path):
    # A Latin-1 name (legal on Linux, common on old shares), a line break and an escape sequence.
    raw = [b"M\xfcller.csv", b"b\nc.csv", b"esc\x1b]0;owned\x07.csv"]
    for name in raw:
        (tmp_path / os.fsdecode(name)).write_bytes((source / CURVE).read_bytes())
    (tmp_path / os.fsdecode(b"bad\xff\x1b[2J.csv")).write_text("delta,P\n1,2\n")
    paths = sorted(tmp_path.iterdir())
    items = layerjkr.fit_files(paths, str(source / SCENE), free="E,w,delta0,P0", branch="all")
    assert [it.source for it in items] == [str(p) for p in paths]  # surrogates where the bytes are not UTF-8
    assert [os.fsencode(it.source) for it in items] == [os.fsencode(p) for p in paths]
    bad = next(it for it in items if not it.ok)
    assert "\x1b" not in bad.error and "\\x1b[2J" in bad.error  # printable, and says what it was
    assert "bad\\xff" in bad.error
    good = [it for it in items if it.ok]
    assert len(good) == 3
    for it in good:  # each result's record names its file, reversibly and as valid JSON
        path = it.result.provenance["inputs"][0]["path"]
        json.dumps(path).encode("utf-8")
        assert "\x1b" not in path


def test_exception_messages_print_control_characters_escaped():
    with pytest.raises(layerjkr.InputError) as e:
        layerjkr.scene({"indenter": {"shape": "\x1b]0;owned\x07", "R": 1e-5},
                        "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}})
    assert "\x1b" not in str(e.value) and "\\x1b]0;owned\\x07" in str(e.value)


@pytest.mark.parametrize("options, says", [
    (dict(points=-1), r"points = -1 is invalid; valid range: \[2, 100000\]"),
    (dict(points=10**9), r"points = 1000000000 is invalid"),
    (dict(seed=-1), r"seed = -1 is invalid; valid range: \[0, 2\*\*64 - 1\]"),
    (dict(speed=1e-6, dwell=1e9), r"dwell = 1000000000 is invalid"),
    (dict(noise=1e308), r"noise = 1e\+308 is invalid"),
    (dict(speed=1e-316), r"speed = 1e-316 is invalid"),
])
def test_simulate_bounds_its_options_before_the_work(options, says):
    # Issue 41: raw pybind TypeErrors for points=-1 and seed=-1, MemoryError for points=10**9
    # and dwell=1e9, inf forces and nan times for the noise and speed: all ValueErrors now.
    scene = {"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space", "E": 2000, "nu": 0.5}}
    with pytest.raises(ValueError, match=says):
        layerjkr.simulate(scene, max_indentation=1e-6, **options)


def test_every_argument_is_checked_by_its_own_name(source):
    # Issue 41: an audit passing bad values to every argument of every function found pybind's
    # "incompatible function arguments" for integers past 32 bits, bare "'NoneType' object is not
    # iterable", and the library's internal names (cantilever_stiffness, RetractDrive: rate).
    d, P, seg = curve_arrays(source)
    scene = str(source / SCENE)
    for name in ("max_iterations", "starts"):
        with pytest.raises(layerjkr.InputError, match="%s = 10+ is out of range" % name):
            layerjkr.fit(d, P, scene, free="E", **{name: 10**19})
    with pytest.raises(layerjkr.InputError, match="jobs = -10+ is out of range"):
        layerjkr.fit_batch([(d, P)], scene, free="E", jobs=-10**19)
    with pytest.raises(layerjkr.InputError, match=r"segment\[0\] = 10+ is not a segment label"):
        layerjkr.fit(d, P, scene, free="E", segment=[10**30] * len(d))
    with pytest.raises(TypeError, match="free must be a string or a sequence"):
        layerjkr.fit(d, P, scene, free=None)
    with pytest.raises(TypeError, match="delta must be an array of numbers"):
        layerjkr.fit(object(), P, scene, free="E")
    with pytest.raises(TypeError, match=r"curves\[0\] must be a pair"):
        layerjkr.fit_batch([1, 2], scene, free="E")
    with pytest.raises(TypeError, match="paths must be a sequence"):
        layerjkr.fit_files(None, scene, free="E")
    with pytest.raises(TypeError, match="path must be a path"):
        layerjkr.read_instrument(None)
    with pytest.raises(layerjkr.InputError, match=r"spring_constant = -1 is invalid; valid range: finite and > 0 \[N/m\]"):
        layerjkr.fit(d, P, scene, free="E", spring_constant=-1)
    with pytest.raises(layerjkr.InputError, match=r"retract_speed = -1 is invalid"):
        layerjkr.summary(scene, retract_speed=-1)
    # A bytes path is a path, as the CLI takes any name the file system gives.
    ibw = os.fsencode(str(source / "tests/data/instrument/IgorIBWReader_ForceCurve.ibw"))
    assert len(layerjkr.read_instrument(ibw)) == 1
    assert layerjkr.fit_files([ibw], scene, free="E")[0].source.endswith("IgorIBWReader_ForceCurve.ibw")


def test_a_batch_says_when_curves_fail_and_a_missing_file_is_an_error(source, tmp_path):
    # Issue 43: a batch goes on past a bad curve, but never in silence; a name that is nothing is the
    # caller's error, not a failed curve.
    d, P, seg = curve_arrays(source)
    scene = str(source / SCENE)
    flat = (np.linspace(0.0, 1e-6, 50), np.zeros(50))  # P constant: nothing to fit
    with pytest.warns(layerjkr.ModelWarning, match=r"1 of 2 curves failed .* the first: curve 1: P is constant"):
        results = layerjkr.fit_batch([(d, P), flat], scene, free="E,delta0,P0")
    assert results[0].ok and not results[1].ok
    with pytest.warns(layerjkr.ModelWarning, match=r"every curve of the batch failed \(2 of 2\)"):
        layerjkr.fit_batch([flat, flat], scene, free="E")
    missing = tmp_path / "missing.csv"
    with pytest.raises(layerjkr.InputError, match=r"paths\[1\] = .*missing\.csv.*: no such file or directory"):
        layerjkr.fit_files([str(source / "data/curves/hydrogel_film_two_term.csv"), missing], scene, free="E")
