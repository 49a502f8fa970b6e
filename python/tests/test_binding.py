"""The Python binding against the C++ CLI: same numbers to the last bit, numpy handling,
exceptions, GIL release and memory."""
import json
import subprocess
import threading

import numpy as np
import pytest

import layerjkr

SCENE = "data/scenes/hydrogel_film_two_term.json"


def run_cli(cli, source, *args):
    r = subprocess.run([cli, *args], cwd=source, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_curve_equals_cli_bit_for_bit(cli, source):
    a = np.linspace(1e-7, 2e-6, 200)
    c = layerjkr.curve(str(source / SCENE), a)
    rows = run_cli(cli, source, "curve", SCENE, "--at", ",".join(repr(float(x)) for x in a)).splitlines()
    assert rows[0] == "a,P,delta,P_H,delta_H,S,error_est"
    table = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    for k, name in enumerate(["a", "P", "delta", "P_H", "delta_H", "S", "error_est"]):
        assert np.array_equal(c[name], table[:, k]), name
        assert c[name].dtype == np.float64 and c[name].shape == (200,)


def test_summary_equals_cli(cli, source):
    for scene in ["data/scenes/hydrogel_film_two_term.json", "data/scenes/sphere_pdms_film_two_term.json"]:
        assert layerjkr.summary(str(source / scene)) == json.loads(run_cli(cli, source, "summary", scene))


def test_scene_from_dict_equals_file(source):
    spec = json.loads((source / SCENE).read_text())
    a = [2e-7, 5e-7]
    assert np.array_equal(layerjkr.curve(spec, a)["P"], layerjkr.curve(str(source / SCENE), a)["P"])


def load_sample(source):
    lines = (source / "data/curves/hydrogel_film_two_term.csv").read_text().splitlines()
    body = [line for line in lines if not line.startswith("#")]
    assert body[0] == "delta,P,segment"
    data = np.array([[float(v) for v in line.split(",")] for line in body[1:]])
    return data[:, 0], data[:, 1], data[:, 2].astype(int)


def test_fit_equals_cli(cli, source, tmp_path):
    delta, P, segment = load_sample(source)
    r = layerjkr.fit(delta, P, scene=str(source / SCENE), free=["E", "w", "delta0", "P0"], segment=segment, branch="all")
    out = tmp_path / "report.json"
    run_cli(cli, source, "fit", "data/curves/hydrogel_film_two_term.csv", "--scene", SCENE, "--free", "E,w,delta0,P0",
            "--branch", "all", "--out", str(out))
    ref = json.loads(out.read_text())
    for name, p in ref["parameters"].items():
        assert r.values[name] == p["value"], name
        assert r.stderr[name] == p["stderr"], name
    assert r.as_dict()["correlation"] == ref["correlation"]
    assert r.converged and r.identifiable
    assert r.P_fit.shape == r.P.shape == r.delta.shape
    assert "E" in r.report()


def test_dtypes_shapes_and_contiguity(source):
    scene = layerjkr.scene(str(source / SCENE))
    a64 = np.linspace(1e-7, 1e-6, 10)
    ref = layerjkr.curve(scene, a64)["P"]
    strided = np.repeat(a64, 2)[::2]
    assert not strided.flags["C_CONTIGUOUS"] or strided.base is not None
    assert np.array_equal(layerjkr.curve(scene, strided)["P"], ref)
    assert np.array_equal(layerjkr.curve(scene, list(a64))["P"], ref)
    a32 = a64.astype(np.float32)
    assert np.array_equal(layerjkr.curve(scene, a32)["P"], layerjkr.curve(scene, a32.astype(np.float64))["P"])
    with pytest.raises(layerjkr.InputError, match="1-D"):
        layerjkr.curve(scene, a64.reshape(2, 5))


def test_errors_are_the_library_messages(source):
    scene = layerjkr.scene(str(source / SCENE))
    with pytest.raises(layerjkr.InputError, match="contact radius a = nan"):
        layerjkr.curve(scene, [1e-7, np.nan])
    with pytest.raises(ValueError):  # InputError is a ValueError too
        layerjkr.curve(scene, [-1.0])
    spec = json.loads((source / SCENE).read_text())
    spec["colour"] = "blue"
    with pytest.raises(layerjkr.Error, match="colour"):
        layerjkr.scene(spec)
    delta, P, segment = load_sample(source)
    with pytest.raises(layerjkr.InputError, match="unknown option 'brunch'"):
        layerjkr.fit(delta, P, scene=scene, free="E,w", brunch="all")
    with pytest.raises(layerjkr.InputError, match="--branch"):
        layerjkr.fit(delta, P, scene=scene, free="E,w", branch="sideways")
    with pytest.raises(layerjkr.InputError, match="--free"):
        layerjkr.fit(delta, P, scene=scene, free="E,colour")
    with pytest.raises(layerjkr.InputError):
        layerjkr.scene(42)
    assert issubclass(layerjkr.NumericalError, ArithmeticError) and issubclass(layerjkr.DomainError, layerjkr.Error)


def test_long_calls_release_the_gil(source):
    # While a batch of fits runs in a thread, this thread keeps running Python: with the GIL
    # held for the whole call it would get the interpreter only at the end.
    delta, P, segment = load_sample(source)
    scene = layerjkr.scene(str(source / SCENE))
    curves = [(delta, P)] * 40
    done = threading.Event()
    worker = threading.Thread(target=lambda: (layerjkr.fit_batch(curves, scene, ["E", "w", "delta0"], jobs=1), done.set()))
    ticks = 0
    worker.start()
    while not done.is_set():
        ticks += 1
    worker.join()
    assert ticks > 10000


def test_threaded_batch_equals_serial(source):
    delta, P, segment = load_sample(source)
    scene = layerjkr.scene(str(source / SCENE))
    curves = [(delta, P * (1 + 1e-3 * k)) for k in range(4)]
    serial = layerjkr.fit_batch(curves, scene, "E,w,delta0", jobs=1)
    threaded = layerjkr.fit_batch(curves, scene, "E,w,delta0", jobs=2)
    assert [s["report"]["parameters"] for s in serial] == [t["report"]["parameters"] for t in threaded]
    assert all(s["ok"] for s in serial)


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


def test_no_memory_growth_over_10000_calls(source):
    # 10 000 calls through each path that allocates across the boundary: a dict scene, an
    # exception, and (2 000 times, each ~2 ms of C++) a curve's arrays.
    spec = json.loads((source / SCENE).read_text())
    scene = layerjkr.scene(spec)
    a = np.linspace(1e-7, 1e-6, 5)

    def calls(n):
        for i in range(n):
            layerjkr.scene(spec)
            try:
                layerjkr.curve(scene, [np.nan])
            except layerjkr.InputError:
                pass
            if i % 5 == 0:
                layerjkr.curve(scene, a)

    calls(500)
    before = rss_bytes()
    calls(10000)
    assert rss_bytes() - before < 4 * 2**20


def test_callable_profile_against_the_closed_form_sphere(source):
    # A Python callable (vectorised or not) as the indenter: the spherical cap sampled on 201
    # radii against the library's own sphere. Measured: 1.2e-8 in P with 501 samples.
    import math
    spec = json.loads((source / SCENE).read_text())
    R = 1e-5
    sphere = dict(spec, indenter={"shape": "sphere", "R": R})
    a = np.array([3e-7, 1e-6, 1.8e-6])
    truth = layerjkr.curve(sphere, a)
    vectorised = layerjkr.scene(spec, profile=lambda r: R - np.sqrt(R * R - r * r), r_max=4e-6, samples=201)
    scalar = layerjkr.scene(spec, profile=lambda r: R - math.sqrt(R * R - r * r), r_max=4e-6, samples=201)
    for s in (vectorised, scalar):
        c = layerjkr.curve(s, a)
        assert np.max(np.abs(c["P"] / truth["P"] - 1)) < 1e-6
        assert s.profile.startswith("table(201 points")
    with pytest.raises(layerjkr.InputError, match="r_max"):
        layerjkr.scene(spec, profile=lambda r: r * r)
    with pytest.raises(layerjkr.InputError, match="non-finite"):
        layerjkr.scene(spec, profile=lambda r: np.log(r), r_max=1e-6)
    with pytest.raises(layerjkr.Error):
        layerjkr.scene(spec, profile=lambda r: -r, r_max=1e-6)  # not an indenter: falls away
