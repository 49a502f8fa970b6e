"""Instrument files through the binding (needs ../shared/data/instrument: skipped without it)."""
import concurrent.futures
import json
import pickle

import numpy as np
import pytest

import layerjkr


def test_read_instrument_matches_the_reference(instrument_dir, source):
    reference = json.loads((instrument_dir / "reference.json").read_text())
    curves = layerjkr.read_instrument(instrument_dir / "fmt-jpk-fd_map2x2_extracted.jpk-force-map")
    assert len(curves) == 4
    assert curves[0]["delta"].dtype == np.float64 and curves[0]["segment"].shape == curves[0]["P"].shape
    assert all(c["spring_constant"] > 0 for c in curves)
    # Each sample's time from the segments' durations, as `layerjkr export` writes it: fits in time need it.
    assert curves[0]["t"].shape == curves[0]["P"].shape and np.all(np.diff(curves[0]["t"]) > 0)
    assert curves[0]["t"][0] == 0.0
    assert reference  # the C++ suite checks every value; here: the binding reads the same file
    with pytest.raises(layerjkr.InputError):
        layerjkr.read_instrument(source / "README.md")


def test_fit_files_on_an_archive_equals_the_cli_map(instrument_dir, source, cli, tmp_path):
    import subprocess
    archive = instrument_dir / "fmt-jpk-fd_spot3-0192.jpk-force"
    scene = str(source / "data/scenes/hydrogel_film_two_term.json")
    items = layerjkr.fit_files([archive], scene, free=["E", "delta0", "P0"], jobs=1)
    assert len(items) == 1
    out = tmp_path / "map.csv"
    r = subprocess.run([cli, "fit-map", str(archive), "--scene", scene, "--free", "E,delta0,P0", "--jobs", "1", "--out",
                        str(out)], capture_output=True, text=True)
    assert r.returncode == (0 if items[0].ok else 4), r.stderr  # 4: no curve fitted
    import csv
    header, row = list(csv.reader(out.read_text().splitlines()))[:2]  # message cells are quoted
    cells = dict(zip(header, row))
    assert items[0].ok == (cells["status"] == "ok")
    assert items[0].curve == (int(cells["curve"]) if cells["curve"] else None)
    if items[0].ok:
        assert items[0].result.values["E"] == float(cells["E"])
        stderr = float(cells["E_stderr"]) if cells["E_stderr"] else float("nan")  # empty: no error bar
        assert np.array_equal(items[0].result.errors["E"], stderr, equal_nan=True)


# Ranges and random access (issue #22): a range or an opened file's curves are the whole read's,
# bit for bit, in JPK maps, a QI map and a NanoScope force volume.

QI = "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data"
MAP = "fmt-jpk-fd_map2x2_extracted.jpk-force-map"


def same_curve(a, b):
    """The same dict, bit for bit: arrays by their bytes and dtype, numbers by their bits (NaN too)."""
    assert sorted(a) == sorted(b)
    for key in a:
        if isinstance(a[key], np.ndarray):
            assert a[key].dtype == b[key].dtype and a[key].tobytes() == b[key].tobytes(), key
        else:
            assert type(a[key]) is type(b[key]) and np.array(a[key]).tobytes() == np.array(b[key]).tobytes(), key
    return True


def same_curves(xs, ys):
    assert len(xs) == len(ys)
    return all(same_curve(x, y) for x, y in zip(xs, ys))


@pytest.mark.parametrize("name", [QI, MAP])
def test_a_range_is_the_slice_of_the_whole_read(instrument_dir, name):
    path = instrument_dir / name
    whole = layerjkr.read_instrument(path)
    assert len(whole) == 4
    for a, b in [(0, 4), (1, 3), (3, 4), (2, 100), (0, 0), (4, 4), (9, 12)]:
        assert same_curves(layerjkr.read_instrument(path, curves=(a, b)), whole[a:b]), (a, b)
        assert same_curves(layerjkr.read_instrument(path, curves=slice(a, b)), whole[a:b]), (a, b)
    assert same_curves(layerjkr.read_instrument(path, curves=slice(2, None)), whole[2:])
    assert same_curves(layerjkr.read_instrument(path, curves=slice(None, 3, 1)), whole[:3])
    assert same_curves(layerjkr.read_instrument(path, curves=(np.int64(1), np.int32(2))), whole[1:2])


@pytest.mark.parametrize("name", [QI, MAP])
def test_open_instrument_reads_any_curve_as_read_instrument(instrument_dir, name):
    path = instrument_dir / name
    whole = layerjkr.read_instrument(path)
    with layerjkr.open_instrument(path) as f:
        assert len(f) == 4
        h = f.header
        assert h["path"] == str(path) and h["format"] == name.split(".")[-1]
        assert set(h) == {"path", "format", "instrument", "software", "grid_shape", "grid_size", "grid_center"}
        assert h["grid_shape"][0] * h["grid_shape"][1] >= 4
        for i in [3, 0, 2, 1, -1, -4]:  # any order, negative positions as a sequence's
            assert same_curve(f[i], whole[i])
            assert f.curve_number(i) == whole[i]["index"]
        assert same_curves(f[1:3], whole[1:3]) and same_curves(f[::-2], whole[::-2]) and f[5:9] == []
        assert same_curves(list(f), whole)
        with pytest.raises(IndexError, match="outside"):
            f[4]
        with pytest.raises(IndexError):
            f.curve_number(-5)
        with pytest.raises(TypeError, match="curve position"):
            f[1.0]
        again = pickle.loads(pickle.dumps(f))  # as a path: Dask ships it to a worker that reopens it
        assert len(again) == 4 and same_curve(again[2], whole[2])
        assert "4 curves" in repr(f)
    assert f.closed and f.header["path"] == str(path)
    with pytest.raises(ValueError, match="closed"):
        f[0]


def test_threads_read_one_open_file_at_once(instrument_dir):
    # The GIL is released while reading and the reader is thread-safe: the same curves come back.
    path = instrument_dir / QI
    whole = layerjkr.read_instrument(path)
    f = layerjkr.open_instrument(path)
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda i: f[i % 4], range(64)))
    assert all(same_curve(c, whole[i % 4]) for i, c in enumerate(got))


@pytest.mark.parametrize("curves", [slice(0, 4, 2), slice(None, None, -1), slice(-1, None), slice(None, -1),
                                    (-1, 2), (3, 1), slice(3, 1)])
def test_a_bad_range_is_a_value_error_naming_curves(instrument_dir, curves):
    with pytest.raises(ValueError, match="curves"):
        layerjkr.read_instrument(instrument_dir / QI, curves=curves)
    with pytest.raises(ValueError, match="curves"):
        layerjkr.fit_files([instrument_dir / QI], {"indenter": {"shape": "paraboloid", "R": 4e-8},
                                                   "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}},
                           curves=curves)


@pytest.mark.parametrize("curves", ["0:4", (0, 1, 2), (0.0, 2), (None, 2), (0, None), [0, 2], 3])
def test_a_range_that_is_not_a_slice_or_pair_is_a_type_error(instrument_dir, curves):
    with pytest.raises(TypeError, match="curves"):
        layerjkr.read_instrument(instrument_dir / QI, curves=curves)


HERTZ = {"indenter": {"shape": "paraboloid", "R": 4e-8}, "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}}


def test_fit_files_fits_only_the_range(instrument_dir):
    path = instrument_dir / QI
    whole = layerjkr.fit_files([path], HERTZ, free="E,delta0,P0")
    part = layerjkr.fit_files([path], HERTZ, free="E,delta0,P0", curves=(1, 3))
    assert [it.source for it in part] == [it.source for it in whole[1:3]]
    for a, b in zip(part, whole[1:3]):
        assert (a.curve, a.grid_x, a.grid_y, a.ok, a.error) == (b.curve, b.grid_x, b.grid_y, b.ok, b.error)
        if a.ok:
            assert a.result.values.tobytes() == b.result.values.tobytes()
    assert [it.source for it in layerjkr.fit_files([path], HERTZ, free="E,delta0,P0", curves=slice(2, None))] == \
        [it.source for it in whole[2:]]
    none = layerjkr.fit_files([path], HERTZ, free="E,delta0,P0", curves=(4, 10))
    assert len(none) == 1 and not none[0].ok and "selects none of its 4 curves" in none[0].error


def test_a_nanoscope_file_reads_whole_in_ranges_and_by_position(instrument_dir):
    bruker = instrument_dir / "bruker"
    reference = {f["file"]: f for f in json.loads((bruker / "reference.json").read_text())["files"]}
    for path in sorted(bruker.glob("*.spm")):
        whole = layerjkr.read_instrument(path)
        assert len(whole) == reference[path.name]["n_curves"]
        assert all(c["spring_constant"] > 0 and c["P"].size == c["delta"].size > 0 for c in whole)
        with layerjkr.open_instrument(path) as f:
            assert len(f) == len(whole) and f.header["format"] == "nanoscope"
            n = len(f)
            for i in sorted({0, n // 2, n - 1}):
                assert same_curve(f[i], whole[i]) and f.curve_number(i) == whole[i]["index"]
        a, b = n // 3, n // 3 + max(1, n // 4)
        assert same_curves(layerjkr.read_instrument(path, curves=(a, b)), whole[a:b])


def test_the_default_fit_of_a_qi_curve_frees_its_baseline_or_warns(source):
    # Issue 40: with P0 fixed the bundled QI map's curve 1 gave E 100x below the P0-free fit, and
    # only warnings about w were shown. The default frees P0; fixing it says what it costs.
    path = source / "data/instrument" / QI
    c = layerjkr.read_instrument(path, curves=(1, 2))[0]
    scene = str(source / "data/scenes/hertz_R40nm.json")
    with_P0 = layerjkr.fit(c["delta"], c["P"], scene, segment=c["segment"], free="E,w,delta0,P0")
    default = layerjkr.fit(c["delta"], c["P"], scene, segment=c["segment"])
    assert default.parameters == with_P0.parameters
    assert default.values["E"] == with_P0.values["E"]
    with pytest.warns(layerjkr.ModelWarning, match="P0 is fixed at 0, and the answer depends on it: with P0 free, E ="):
        fixed = layerjkr.fit(c["delta"], c["P"], scene, segment=c["segment"], free="E,w,delta0")
    assert abs(fixed.values["E"] - with_P0.values["E"]) > 3 * with_P0.errors["E"]
    assert not fixed.identifiable


def test_vendor_exports_read_with_the_calibration_given(source):
    # Issue 41: afmformats' AFM Workshop map (a zip) and NT-MDT text export, which layerjkr did not
    # read; their calibration comes from the arguments, and its absence names them.
    d = source / "tests/data/instrument"
    zip_map = d / "fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip"
    with pytest.raises(layerjkr.InputError, match="sensitivity"):
        layerjkr.read_instrument(zip_map, spring_constant=20)
    curves = layerjkr.read_instrument(zip_map, spring_constant=20, sensitivity=1e-8)
    assert len(curves) == 16 and (curves[1]["grid_x"], curves[1]["grid_y"]) == (1, 0)
    assert curves[0]["P"][0] == pytest.approx(0.6875 * 1e-8 * 20, rel=1e-12)
    nt = d / "fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt"
    scene = str(source / "data/scenes/hertz_R40nm.json")
    bare = layerjkr.fit_files([nt], scene, free="E,delta0,P0")[0]
    assert bare.result is None and "--spring-constant" in bare.error and "--sensitivity" in bare.error
    item = layerjkr.fit_files([nt], scene, free="E,delta0,P0", spring_constant=0.055, sensitivity=61)[0]
    assert item.error is None and item.result.values["E"] > 0


def test_hdf5_is_refused_saying_where_it_is_read(source):
    # The wheel carries no libhdf5 (34 libraries on Debian): the CLI reads afmformats' .h5 exports.
    with pytest.raises(layerjkr.InputError, match="not read by this program.*layerjkr export FILE.h5"):
        layerjkr.read_instrument(source / "tests/data/instrument/fmt-hdf5-fd_version_0.13.3.h5")


def test_a_dwell_file_fitted_in_time_from_python_is_the_clis_fit(instrument_dir, cli, tmp_path):
    # afmformats' stress-relaxation curve: read_instrument's t and segment give Python the CLI's fit.
    import subprocess
    path = instrument_dir / "fmt-jpk-sr_cell1-0008.jpk-force"
    scene = {"indenter": {"shape": "paraboloid", "R": 5e-6},
             "medium": {"type": "half_space", "E": 1000, "nu": 0.5,
                        "viscoelastic": {"law": "power_law", "beta": 0.2, "t0": 1}}}
    c = layerjkr.read_instrument(path)[0]
    r = layerjkr.fit(c["delta"], c["P"], scene, free="E,beta,delta0,P0", segment=c["segment"], t=c["t"],
                     branch="all", spring_constant=c["spring_constant"])
    scene_file = tmp_path / "scene.json"
    scene_file.write_text(json.dumps(scene))
    out = tmp_path / "fit.json"
    run = subprocess.run([cli, "fit", str(path), "--scene", str(scene_file), "--free", "E,beta,delta0,P0",
                          "--branch", "all", "--out", str(out)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    values = {name: p["value"] for name, p in json.loads(out.read_text())["parameters"].items()}
    assert r.values["E"] == pytest.approx(values["E"], rel=1e-9)
    assert r.values["beta"] == pytest.approx(values["beta"], rel=1e-9)
