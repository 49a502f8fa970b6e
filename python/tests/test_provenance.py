"""Provenance in Python: every FitResult says what it was made from - the library's version, the
scene as parsed, every option, and the SHA-256 of its inputs (files, or the arrays' bytes) - and
the scene it records refits to the same numbers bit for bit."""
import hashlib
import json
import os
import pickle

import numpy as np
import pytest

import layerjkr

SCENE = "data/scenes/hydrogel_film_two_term.json"
CURVE = "data/curves/hydrogel_film_two_term.csv"

pytestmark = pytest.mark.filterwarnings("ignore::layerjkr.ModelWarning")


def sha256(data):
    return hashlib.sha256(data).hexdigest()


def load_sample(source):
    lines = [line for line in (source / CURVE).read_text().splitlines() if not line.startswith("#")]
    data = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    return data[:, 0], data[:, 1], data[:, 2].astype(int)


def test_version_is_the_librarys(source):
    r = layerjkr.fit(*load_sample(source)[:2], str(source / SCENE), free="E,delta0")
    assert r.provenance["layerjkr_version"] == layerjkr.__version__ == layerjkr._core.__version__


def test_fit_of_arrays_records_their_bytes_the_scene_file_and_every_option(source):
    delta, P, segment = load_sample(source)
    r = layerjkr.fit(delta, P, str(source / SCENE), free=["E", "w", "delta0", "P0"], segment=segment, branch="all",
                     starts=2, loss="huber", loss_scale=1e-10)
    p = r.provenance
    assert [i["path"] for i in p["inputs"]] == ["delta (float64 array)", "P (float64 array)", "segment (int64 array)"]
    # hashlib over the documented bytes: float64 (int64 for segments), native order, C order.
    assert p["inputs"][0]["sha256"] == sha256(np.ascontiguousarray(delta, dtype=np.float64).tobytes())
    assert p["inputs"][1]["sha256"] == sha256(np.ascontiguousarray(P, dtype=np.float64).tobytes())
    assert p["inputs"][2]["sha256"] == sha256(np.asarray(segment, dtype=np.int64).tobytes())
    assert p["inputs"][0]["size"] == 8 * len(delta)
    assert "csv" not in p  # no file was read
    assert p["scene"]["json"] == json.loads((source / SCENE).read_text())
    assert p["scene"]["sha256"] == sha256((source / SCENE).read_bytes())
    assert p["options"]["free"] == ["E", "w", "delta0", "P0"]
    assert p["options"]["branch"] == "all" and p["options"]["extra_starts"] == 2
    assert p["options"]["loss"] == "huber" and p["options"]["loss_scale"] == 1e-10
    # A list of floats hashes as the float64 array it becomes.
    again = layerjkr.fit(delta.tolist(), P.tolist(), str(source / SCENE), free=["E", "w", "delta0", "P0"],
                         segment=segment.tolist(), branch="all", starts=2, loss="huber", loss_scale=1e-10)
    assert again.provenance == p
    assert pickle.loads(pickle.dumps(r)).provenance == p


def test_the_recorded_scene_refits_bit_for_bit(source):
    delta, P, segment = load_sample(source)
    # A dict scene and a callable profile: both recorded as JSON (the profile as its sampled table).
    spec = json.loads((source / SCENE).read_text())
    s = layerjkr.scene(spec, profile=lambda r: r * r / 2e-5, r_max=1e-5, samples=301)
    r = layerjkr.fit(delta, P, s, free="E,w,delta0,P0", segment=segment, branch="all")
    recorded = r.provenance["scene"]
    assert recorded["file"] is None and recorded["sha256"] is None
    assert recorded["json"]["indenter"]["shape"] == "table"
    assert len(recorded["json"]["indenter"]["r"]) == 301
    again = layerjkr.fit(delta, P, recorded["json"], free="E,w,delta0,P0", segment=segment, branch="all")
    assert again.as_dict() == r.as_dict()
    assert np.array_equal(again.values, r.values) and np.array_equal(again.errors, r.errors)


def test_batch_results_record_their_own_inputs(source, tmp_path):
    delta, P, _ = load_sample(source)
    curves = [(delta, P), (delta[:600], P[:600])]
    results = layerjkr.fit_batch(curves, str(source / SCENE), free="E,delta0", jobs=2)
    for (d, f), b in zip(curves, results):
        assert b.ok
        inputs = b.result.provenance["inputs"]
        assert inputs[0]["sha256"] == sha256(np.ascontiguousarray(d).tobytes())
        assert inputs[1]["sha256"] == sha256(np.ascontiguousarray(f).tobytes())
        assert b.result.provenance["options"]["free"] == ["E", "delta0"]

    # Files: each hashed once, with the CSV options; a FIFO is recorded without being opened.
    a, c = tmp_path / "a.csv", tmp_path / "c.csv"
    a.write_bytes((source / CURVE).read_bytes())
    c.write_bytes((source / CURVE).read_bytes() + b"# another curve file\n")
    fifo = tmp_path / "f.csv"
    os.mkfifo(fifo)
    items = layerjkr.fit_files([a, c, fifo], str(source / SCENE), free="E,w,delta0,P0", branch="all", units="m,N")
    assert [i.ok for i in items] == [True, True, False]
    for path, item in zip([a, c], items):
        p = item.result.provenance
        assert p["inputs"] == [{"path": str(path), "size": path.stat().st_size, "sha256": sha256(path.read_bytes())}]
        assert p["csv"]["length_unit"] == 1.0 and p["csv"]["curve"] == -1
    assert items[0].result.provenance["inputs"] != items[1].result.provenance["inputs"]
