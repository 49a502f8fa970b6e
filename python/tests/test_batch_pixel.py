"""A batch's curve can be looked at (#43): BatchResults.fit_curve(k) fits curve k again with its
samples - the arrays given, or the curve re-read from its file, checked unchanged - to the same
values, and BatchResults.plot(k) draws it; a map pixel's record names its file."""
import os
import shutil

import numpy as np
import pytest

import layerjkr

SOURCE = os.environ.get("LAYERJKR_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
QI = os.path.join(SOURCE, "data", "instrument", "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data")
HERTZ = os.path.join(SOURCE, "data", "scenes", "hertz_R40nm.json")
FILM_CSV = os.path.join(SOURCE, "data", "curves", "hydrogel_film_two_term.csv")
FILM = os.path.join(SOURCE, "data", "scenes", "hydrogel_film_two_term.json")


# The fits' ModelWarnings are part of what they report, not of what these tests check.
pytestmark = pytest.mark.usefixtures("quiet")


def test_a_batch_of_arrays_fits_a_curve_again_to_the_same_values():
    delta, P, segment = np.loadtxt(FILM_CSV, delimiter=",", skiprows=3, unpack=True)
    b = layerjkr.fit_batch([(delta, P), (delta[:3], P[:3])], FILM, free="E,w,delta0,P0")
    again = b.fit_curve(0)
    assert np.array_equal(again.values, b[0].result.values) and np.array_equal(again.errors, b[0].result.errors, equal_nan=True)
    assert again.delta.size == again.P_fit.size >= 500 and b[0].result.delta.size == 0  # the batch kept none
    with pytest.raises(layerjkr.InputError, match=r"results\[1\] \(curve 1\) was not fitted"):
        b.fit_curve(1)
    # Pickled (Dask ships batches), a batch keeps its results but not the way back to its inputs.
    import pickle
    copy = pickle.loads(pickle.dumps(b))
    assert np.array_equal(copy[0].result.values, b[0].result.values)
    with pytest.raises(layerjkr.InputError, match="unpickled"):
        copy.fit_curve(0)
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    top, bottom = b.plot(0)
    assert len(top.lines) >= 2


def test_a_map_pixel_is_read_again_from_its_file():
    b = layerjkr.fit_files([QI], HERTZ, free="E,delta0,P0")
    again = b.fit_curve(2)
    assert np.array_equal(again.values, b[2].result.values)
    assert again.delta.size > 100
    record = b[2].result.provenance["inputs"][0]  # the file, not "file#2" (which is no file)
    assert record["path"].endswith(".jpk-qi-data") and record["sha256"] and "error" not in record


def test_a_changed_file_is_not_read_again_silently(tmp_path):
    path = tmp_path / "curve.csv"
    shutil.copyfile(FILM_CSV, path)
    b = layerjkr.fit_files([str(path)], FILM, free="E,w,delta0,P0", branch="all")
    assert np.array_equal(b.fit_curve(0).values, b[0].result.values)
    with open(path, "a") as f:
        f.write("\n")
    with pytest.raises(layerjkr.InputError, match="changed since the batch read it"):
        b.fit_curve(0)
