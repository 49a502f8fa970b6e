"""fit_files(report=...) and fit_batch(report=...): the page's embedded data are the results'
values exactly; a bad report directory raises InputError before any fitting."""
import json
import re

import numpy as np
import pytest

import layerjkr

from conftest import SOURCE

CURVE = SOURCE / "data" / "curves" / "hydrogel_film_two_term.csv"
SCENE = str(SOURCE / "data" / "scenes" / "hydrogel_film_two_term.json")
FREE = ["E", "w", "delta0", "P0"]


def _data(page):
    text = page.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>\n<!-- layerjkr force-map report")
    m = re.search(r'<script type="application/json" id="layerjkr-data">(.*?)</script>', text, re.S)
    return json.loads(m.group(1))


def test_fit_files_report_holds_the_results(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("delta,P\n1,oops\n")
    results = layerjkr.fit_files([CURVE, CURVE, bad], SCENE, free=FREE, branch="all", jobs=2, report=tmp_path / "rep")
    assert [r.result is not None for r in results] == [True, True, False]
    d = _data(tmp_path / "rep" / "index.html")
    c = d["columns"]
    assert d["count"] == 3 and d["free"] == FREE
    for i, r in enumerate(results):
        assert c["file"][i] == r.source
        if r.result is None:
            assert c["quality"][i] == "failed" and c["error"][i] == r.error and d["curves"][i] is None
            continue
        for p in FREE:
            assert c[p][i] == r.result.values[p]
            err = r.result.errors[p]
            assert (c[p + "_stderr"][i] is None) if err is None or np.isnan(err) else c[p + "_stderr"][i] == err
        assert c["rms_residual"][i] == r.result.rms_residual
        assert 0 < len(d["curves"][i]["delta"]["codes"])
    assert [v["kind"] for v in d["views"]] == ["index"]
    # Only the report's own file is left: the temporary one was renamed over it.
    assert [p.name for p in (tmp_path / "rep").iterdir()] == ["index.html"]
    # An earlier report is replaced.
    layerjkr.fit_files([CURVE], SCENE, free=FREE, branch="all", report=tmp_path / "rep")
    assert _data(tmp_path / "rep" / "index.html")["count"] == 1


def test_fit_batch_report(tmp_path):
    delta = np.linspace(0.0, 1e-6, 400)
    P = 1e3 * np.clip(delta - 4e-7, 0.0, None) ** 1.5
    results = layerjkr.fit_batch([(delta, P), (delta, P * 2)], SCENE, free=["E", "delta0"], report=tmp_path / "rep")
    d = _data(tmp_path / "rep" / "index.html")
    assert d["count"] == 2 and d["views"][0]["cells"] == [0, 1]
    for i, r in enumerate(results):
        if r.result is not None:
            assert d["columns"]["E"][i] == r.result.values["E"]


def test_bad_report_directory_raises_before_fitting(tmp_path):
    plain = tmp_path / "plain.txt"
    plain.write_text("x")
    with pytest.raises(layerjkr.InputError, match="report .*plain.txt: exists and is not a directory"):
        layerjkr.fit_files([CURVE], SCENE, free=FREE, report=plain)
    busy = tmp_path / "busy"
    busy.mkdir()
    (busy / "mine.txt").write_text("mine")
    with pytest.raises(layerjkr.InputError, match=r"is not a previous report \(it holds mine.txt\)"):
        layerjkr.fit_batch([(np.arange(10.0), np.arange(10.0))], SCENE, free=["E"], report=busy)
    with pytest.raises(layerjkr.InputError, match="cannot create the directory"):
        layerjkr.fit_files([CURVE], SCENE, free=FREE, report=plain / "sub")
