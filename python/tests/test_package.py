"""The package as notebook users meet it (issue 36): modules under 400 lines behind an unchanged
public API, results that become models again (r.scene, r.eval), units and forgiving names,
labelled prints, an HTML table and a plot."""
import json
import os
import pathlib
import pickle

import numpy as np
import pytest

import layerjkr

JKR = {"indenter": {"shape": "paraboloid", "R": 1e-5},
       "medium": {"type": "layer", "E": 2e4, "nu": 0.49, "h": 5e-6, "base": "bonded"}, "model": "exact", "w": 1e-4}
PUBLIC = ["__version__", "Error", "DomainError", "InputError", "NumericalError", "ModelWarning", "Scene",
          "simulate", "Simulation", "fit_joint", "JointFitResult", "AutoChoice", "AdhesionCheck", "FixedGrips",
          "ModelError", "Curve", "Summary", "NamedArray", "FitResult", "BatchResult", "BatchResults", "Instrument", "scene", "curve",
          "summary", "fit", "fit_batch", "fit_files", "read_instrument", "open_instrument"]


def retract(noise=2e-10, seed=3):
    return layerjkr.simulate(JKR, max_indentation=2e-6, points=300, noise=noise, seed=seed, branch="retract")


@pytest.fixture(scope="module")
def fitted():
    s = retract()
    guess = {**JKR, "medium": {**JKR["medium"], "E": 5e4}, "w": 3e-4}
    return s, layerjkr.fit(s.delta, s.P, guess, free="E, w, delta0", branch="retract",
                           segment=np.ones(s.P.size, dtype=int))


def test_modules_are_small_and_the_public_api_is_unchanged():
    package = pathlib.Path(layerjkr.__file__).parent
    sizes = {p.name: len(p.read_text().splitlines()) for p in package.glob("*.py")}
    assert len(sizes) > 5
    assert all(n < 400 for n in sizes.values()), sizes
    assert layerjkr.__all__ == PUBLIC
    for name in PUBLIC[1:]:
        assert hasattr(layerjkr, name)
        module = getattr(getattr(layerjkr, name), "__module__", "layerjkr")
        assert module in ("layerjkr", "layerjkr._core"), (name, module)


def test_fit_scene_round_trips(fitted):
    s, r = fitted
    assert r.converged
    assert abs(r.values["E"] - 2e4) < 3 * r.errors["E"]
    scene = r.scene
    assert isinstance(scene, layerjkr.Scene)
    assert json.loads(scene.json)["medium"]["E"] == pytest.approx(r.values["E"], rel=1e-15)
    # Simulated again from the fitted scene: the same curve within the noise.
    again = layerjkr.simulate(scene, max_indentation=2e-6, points=300, branch="retract",
                              delta0=r.values["delta0"])
    assert np.sqrt(np.mean((again.P - s.P) ** 2)) < 2.0 * 2e-10
    assert layerjkr.summary(scene).pull_off_force == pytest.approx(layerjkr.summary(JKR).pull_off_force, rel=0.02)
    # eval: the fitted force at the fit's own samples is its P_fit.
    span = np.ptp(r.P_fit)
    assert np.max(np.abs(r.eval(r.delta) - r.P_fit)) < 2e-3 * span
    # Issue 41: one extra point far out (1 cm) changed the forces at 20-80 nm 28-280x; eval([nan])
    # returned P0. Each point's value is its own now; NaN in, NaN out.
    some = r.delta[::37]
    assert np.array_equal(r.eval(some), r.eval(np.append(some, 2e-5))[:-1])
    assert np.array_equal(r.eval(some[::-1]), r.eval(some)[::-1])
    out = r.eval([np.nan, some[3], np.inf])
    assert np.isnan(out[0]) and np.isnan(out[2]) and out[1] == r.eval([some[3]])[0]
    clone = pickle.loads(pickle.dumps(r))
    assert type(clone) is layerjkr.FitResult and clone.scene.json == scene.json


def test_a_callable_profile_comes_back_as_its_table_and_a_fit_in_time_has_no_eval():
    s = retract(noise=0.0)
    built = layerjkr.scene(JKR, profile=lambda r: r * r / 2e-5, r_max=1e-4)
    r = layerjkr.fit(s.delta, s.P, built, free="E,delta0", branch="retract", segment=np.ones(s.P.size, dtype=int))
    assert '"table"' in json.dumps(r.provenance["scene"]["json"])  # the sampled profile, as recorded
    assert layerjkr.summary(r.scene).pull_off_force == pytest.approx(layerjkr.summary(JKR).pull_off_force, rel=1e-3)
    cell = {"indenter": {"shape": "paraboloid", "R": 5e-6},
            "medium": {"type": "half_space", "E": 2000, "nu": 0.49, "viscoelastic": {"law": "sls", "E_inf": 800, "tau": 0.2}},
            "model": "half_space"}
    t = layerjkr.simulate(cell, max_indentation=1e-6, speed=2e-6, points=60, noise=1e-12)
    rt = layerjkr.fit(t.delta, t.P, cell, free="E,E_inf,tau,delta0", t=t.t, segment=t.segment, branch="all")
    assert rt.scene.json  # a model again: simulate(rt.scene, speed=...) is its curve
    with pytest.raises(layerjkr.InputError, match="depends on the history"):
        rt.eval(t.delta)


def test_units_and_the_hint_when_data_are_not_si():
    s = retract()
    seg = np.ones(s.P.size, dtype=int)
    si = layerjkr.fit(s.delta, s.P, JKR, free="E w delta0", branch="retract", segment=seg)
    nano = layerjkr.fit(s.delta * 1e9, s.P * 1e9, JKR, free="E,w,delta0", branch="retract", segment=seg,
                        units="nm,nN")
    assert nano.values["E"] == pytest.approx(si.values["E"], rel=1e-6)
    with pytest.raises(layerjkr.Error, match='units="nm,nN"'):
        layerjkr.fit(s.delta * 1e9, s.P * 1e9, JKR, free="E,w,delta0", branch="retract", segment=seg)
    with pytest.raises(layerjkr.InputError, match="units"):
        layerjkr.fit(s.delta, s.P, JKR, units="furlongs,N")


def test_free_names_are_forgiving_and_wrong_ones_get_the_closest():
    s = retract()
    with pytest.raises(layerjkr.InputError, match='did you mean "w"'):
        layerjkr.fit(s.delta, s.P, JKR, free="E, W")
    with pytest.raises(layerjkr.InputError, match='did you mean "delta0"'):
        layerjkr.fit(s.delta, s.P, JKR, free=["E", "delta_0"])


def test_prints_are_labelled_and_notebooks_get_a_table(fitted):
    _, r = fitted
    text = str(r.values)
    assert text.splitlines()[0].startswith("E ") and "w " in text and "delta0" in text
    matrix = str(r.correlation).splitlines()
    assert matrix[0].split() == ["E", "w", "delta0"] and matrix[1].split()[0] == "E"
    table = r._repr_html_()
    assert "<table>" in table and "delta0" in table and "Pa" in table


def test_plot_draws_data_fit_and_residuals(fitted):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    _, r = fitted
    top, bottom = r.plot()
    assert len(top.lines) >= 2 and len(bottom.lines) >= 1
    assert top.lines[0].get_xdata().size > 100
    # Issue 43: SI-prefixed ticks (pN, um), not N and m under a 1e-10 offset.
    from matplotlib.ticker import EngFormatter
    assert isinstance(top.yaxis.get_major_formatter(), EngFormatter) and top.yaxis.get_major_formatter().unit == "N"
    assert isinstance(bottom.xaxis.get_major_formatter(), EngFormatter) and bottom.xaxis.get_major_formatter().unit == "m"
    top.figure.canvas.draw()
    labels = [t.get_text() for t in top.get_yticklabels() if t.get_text()]
    assert labels and all(l.endswith("N") for l in labels) and "e-" not in top.yaxis.get_offset_text().get_text()


def grid_results(fitted):
    """A 3 x 2 map of one fit's result (one pixel failed, one missing), as fit_files returns."""
    _, r = fitted
    items, quality = [], []
    for k in range(5):
        gx, gy = k % 3, k // 3
        failed = k == 4
        items.append(layerjkr.BatchResult(source="map.jpk-qi-data#%d" % k, curve=k, x=1e-6 * gx + 5e-6,
                                          y=2e-6 * gy, grid_x=gx, grid_y=gy, result=None if failed else r,
                                          error="cannot read" if failed else None))
        quality.append("failed" if failed else "ok")
    return layerjkr.BatchResults(items, quality)


def test_batch_results_become_tables_images_and_tiffs(fitted, tmp_path):
    _, r = fitted
    b = grid_results(fitted)
    assert isinstance(b, list) and len(b) == 5
    image = b.image("E")
    assert image.shape == (2, 3)
    assert image[0, 0] == r.values["E"] and np.isnan(image[1, 1]) and np.isnan(image[1, 2])
    assert b.image("E_stderr")[0, 1] == r.errors["E"]
    with pytest.raises(layerjkr.InputError, match="not a field"):
        b.image("sigma0")
    df = b.to_pandas()
    assert list(df.columns[:8]) == ["file", "curve", "x", "y", "grid_x", "grid_y", "status", "error"]
    assert list(df.columns[-3:]) == ["quality", "warnings", "notices"]
    assert list(df["status"]) == ["ok"] * 4 + ["error"] and df["quality"].iloc[4] == "failed"
    assert df["E"].iloc[0] == r.values["E"] and df["identifiability"].iloc[0] == "yes"
    ds = b.to_xarray()
    assert ds["E"].shape == (2, 3) and ds["E"].attrs["units"] == "Pa"
    assert ds.x.attrs["units"] == "m" and np.allclose(ds.x.values, [5e-6, 6e-6, 7e-6])
    assert np.allclose(ds.y.values, [0.0, 2e-6])
    assert np.isnan(ds["w"].values[1, 1])
    path = tmp_path / "E.tiff"
    b.to_tiff("E", path)
    # A name that is not UTF-8 (bytes, or os.fsdecode's surrogates) is written, not a TypeError.
    raw = bytes(tmp_path) + b"/E-\xff.tiff"
    b.to_tiff("E", raw)
    b.to_tiff("E", os.fsdecode(bytes(tmp_path) + b"/E-\xfe.tiff"))
    assert {b"E-\xff.tiff", b"E-\xfe.tiff"} <= set(os.listdir(bytes(tmp_path)))
    PIL = pytest.importorskip("PIL.Image")  # an independent reader of the TIFF
    with PIL.open(path) as im:
        assert im.size == (3, 2) and im.mode == "F"
        pixels = np.array(im)
    assert pixels[0, 0] == np.float32(r.values["E"]) and np.isnan(pixels[1, 1])
    # Several maps: the image is of one, named.
    two = layerjkr.BatchResults(list(b) + [b[0]._replace(source="other.jpk-force-map#0")], b.quality + ["ok"])
    with pytest.raises(layerjkr.InputError, match="give file="):
        two.image("E")
    assert two.image("E", file="other.jpk-force-map").shape == (1, 1)
    clone = pickle.loads(pickle.dumps(b))
    assert clone.quality == b.quality and isinstance(clone, layerjkr.BatchResults)


def test_bundled_map_to_xarray_has_the_map_shape_in_metres(source):
    # data/instrument's QI map (afmformats, MIT): 4 curves on one row of a 128 x 128 grid.
    qi = source / "data" / "instrument" / "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data"
    scene = {"indenter": {"shape": "sphere", "R": 5e-6}, "medium": {"type": "half_space", "E": 5e3, "nu": 0.5},
             "model": "half_space"}
    b = layerjkr.fit_files([str(qi)], scene, free="E,delta0,P0", jobs=2)
    assert len(b) == 4 and all(it.ok for it in b)
    ds = b.to_xarray()
    assert ds["E"].shape == (1, 4) and ds.sizes == {"y": 1, "x": 4}
    assert ds.x.attrs["units"] == "m" and np.all(np.diff(ds.x.values) > 0)
    assert np.allclose(np.diff(ds.x.values), 1e-5 / 128)  # the grid's pitch: 10 um over 128 pixels
    assert np.all(np.isfinite(ds["E"].values)) and ds["E"].attrs["units"] == "Pa"
    assert b.to_pandas().shape[0] == len(b)
    # Issue 43: long names for plots, the quality per pixel (placed as the values are), the record.
    assert ds["E"].attrs["long_name"] == "Young's modulus"
    assert ds["E_stderr"].attrs["long_name"] == "standard error of the Young's modulus"
    assert list(ds["quality"].values[0]) == b.quality
    assert json.loads(ds.attrs["provenance"])["options"]["free"] == ["E", "delta0", "P0"]


def test_reprs_summarise(fitted):
    # Issue 43: a Scene shows its values, a Simulation and a batch a summary - not 40 kB of arrays
    # or every item in full.
    s, r = fitted
    scene = layerjkr.scene(JKR)
    assert '"E":20000.0' in repr(scene) and '"h":5e-06' in repr(scene)
    text = repr(s)
    assert len(text) < 200 and text.startswith("Simulation(300 samples: retract 300")
    batch = layerjkr.fit_batch([(s.delta, s.P), (s.delta, np.zeros_like(s.P))], JKR, free="E, w, delta0", branch="retract")
    assert repr(batch) == ("BatchResults(2 curves from 2 input(s): 1 fitted, 1 failed; fields E, w, delta0; "
                           "quality: %s)" % ", ".join("%s 1" % q for q in sorted(batch.quality)))
