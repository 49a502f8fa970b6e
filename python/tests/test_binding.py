"""The Python binding against the C++ CLI: same numbers to the last bit, numpy handling,
keyword-only typed options, warnings, exceptions, GIL release and memory."""
import json
import pickle
import re
import subprocess
import threading
import warnings

import numpy as np
import pytest

import layerjkr

SCENE = "data/scenes/hydrogel_film_two_term.json"

# Where a test does not look at them, the answers' ModelWarnings are expected (pytest.warns
# still sees them where a test does).
pytestmark = pytest.mark.filterwarnings("ignore::layerjkr.ModelWarning")


def run_cli(cli, source, *args, stderr=False):
    r = subprocess.run([cli, *args], cwd=source, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return (r.stdout, r.stderr) if stderr else r.stdout


def test_curve_equals_cli_bit_for_bit(cli, source):
    a = np.linspace(1e-7, 2e-6, 200)
    with pytest.warns(layerjkr.ModelWarning) as record:
        c = layerjkr.curve(str(source / SCENE), a)
    out, err = run_cli(cli, source, "curve", SCENE, "--at", ",".join(repr(float(x)) for x in a), stderr=True)
    rows = out.splitlines()
    # The two-term law is ~33 % off the exact layer at a = h/2: the CLI's warning, word for word.
    assert [str(w.message) for w in record] == c.warnings
    assert ["layerjkr: warning: " + w for w in c.warnings] == err.splitlines()
    assert rows[0] == "a,P,delta,P_H,delta_H,S,error_est,c"
    table = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    for k, name in enumerate(["a", "P", "delta", "P_H", "delta_H", "S", "error_estimate"]):
        assert np.array_equal(getattr(c, name), table[:, k]), name
        assert np.array_equal(c[name], table[:, k]), name
        assert c[name].dtype == np.float64 and c[name].shape == (200,)
    assert np.array_equal(c.error_est, c.error_estimate)
    assert c.model == "two_term" and c.reference == "exact" and c.choice is None
    assert len(c.warnings) == 1 and len(c) == 200 and c.seconds > 0


def test_summary_equals_cli(cli, source, tmp_path):
    # Every bundled scene (auto's model_choice among them) and a Filonenko-Borodich medium (T).
    membrane = tmp_path / "membrane.json"
    membrane.write_text(json.dumps({"indenter": {"shape": "paraboloid", "R": 1e-5},
                                    "medium": {"type": "filonenko_borodich", "K": 1e12, "T": 0.1},
                                    "model": "asymptotic", "w": 0.01}))
    scenes = sorted(str(p.relative_to(source)) for p in (source / "data/scenes").glob("*.json")) + [str(membrane)]
    for scene in scenes:
        s = layerjkr.summary(str(source / scene))
        ref = json.loads(run_cli(cli, source, "summary", scene))
        assert s.as_dict() == ref, scene
        assert list(s.as_dict()) == list(ref), scene  # the same keys in the same order
        for key in ref:
            assert s[key] == ref[key], key
        assert s.pull_off_force == ref["pull_off_force"] and s.zero_load_radius == ref["zero_load_radius"]
        assert s.model_error.reference == ref["model_error_estimate"]["reference"]
        assert s.K == ref.get("K") and s.E_star == ref.get("E_star")
        assert (s.T if "T" in ref else s.G) == ref.get("T", ref.get("G"))
        assert (s.choice is None) == ("model_choice" not in ref)
        if s.choice is not None:
            assert s.choice.model == ref["model_choice"]["model"] and s.choice.note.startswith("auto chose model")
    assert "T" in ref and s.T == 0.1 and s.G is None  # the membrane, last
    with pytest.raises(KeyError, match="pull_off"):
        s["pull_off"]


def test_summary_warns_through_model_warning(source):
    # The two-term law on a sphere indenting a PDMS film is estimated ~10 % off the exact layer.
    with pytest.warns(layerjkr.ModelWarning) as record:
        s = layerjkr.summary(str(source / "data/scenes/sphere_pdms_film_two_term.json"))
    assert s.warnings and [str(w.message) for w in record] == s.warnings
    assert re.match(r"model 'two_term' is estimated [0-9.]+ % off its reference model 'exact' in the pull-off force",
                    s.warnings[-1]), s.warnings
    assert record[0].filename == __file__  # stacklevel: the caller's line, as numpy and iminuit do
    assert issubclass(layerjkr.ModelWarning, UserWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning below the threshold
        assert layerjkr.summary(str(source / "data/scenes/sphere_pdms_film_two_term.json"),
                                warning_threshold=0.99).warnings == []


def test_pyramid_scene_states_its_approximation():
    # A four-sided pyramid is its equivalent cone: Bilodeau's F = 0.7453 E* tan(theta) delta^2.
    scene = {"indenter": {"shape": "pyramid", "semi_angle_deg": 35.0, "sides": 4},
             "medium": {"type": "half_space", "E": 1500.0, "nu": 0.5}, "w": 0.0}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a stated model error is a notice: no ModelWarning
        c = layerjkr.curve(scene, [1e-7, 1e-6])
    assert any("4-sided pyramid is modelled by its axisymmetric equivalent cone" in n for n in c.notices)
    assert c["notices"] == c.notices and c.warnings == []
    e_star = 1500.0 / 0.75
    expected = 0.7453 * e_star * np.tan(np.radians(35.0)) * c["delta_H"] ** 2
    np.testing.assert_allclose(c["P_H"], expected, rtol=1e-12)
    with pytest.raises(ValueError, match="indenter.sides"):
        layerjkr.curve(dict(scene, indenter={"shape": "pyramid", "semi_angle_deg": 35.0, "sides": 6}), [1e-7])


def test_auto_curve_reports_its_choice(source):
    c = layerjkr.curve(str(source / "data/scenes/hydrogel_film_auto.json"), [2e-7, 1e-6])
    assert c.choice is not None and c.model == c.choice.model
    assert c.choice.estimated_error <= c.choice.tolerance and "curve" in c.choice.judged_at
    assert c.choice.note.startswith("auto chose model '%s'" % c.model)


def test_stub_and_docstrings(source):
    # _core.pyi names what the compiled module has; every public name has a numpydoc docstring.
    import ast
    stub = ast.parse((source / "python/layerjkr/_core.pyi").read_text())
    stubbed = {n.name for n in stub.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    stubbed |= {n.target.id for n in stub.body if isinstance(n, ast.AnnAssign)}
    compiled = {n for n in dir(layerjkr._core) if not n.startswith("_")} | {"__version__"}
    assert stubbed == compiled
    for name in layerjkr.__all__:
        obj = getattr(layerjkr, name)
        if callable(obj) and not isinstance(obj, type):
            assert "Parameters\n    ----------" in obj.__doc__ and "Returns\n    -------" in obj.__doc__, name
            assert "Raises\n    ------" in obj.__doc__, name
        elif isinstance(obj, type):
            assert obj.__doc__ and len(obj.__doc__) > 20, name


def test_scene_from_dict_equals_file(source):
    spec = json.loads((source / SCENE).read_text())
    a = [2e-7, 5e-7]
    assert np.array_equal(layerjkr.curve(spec, a).P, layerjkr.curve(str(source / SCENE), a).P)


def load_sample(source):
    lines = (source / "data/curves/hydrogel_film_two_term.csv").read_text().splitlines()
    body = [line for line in lines if not line.startswith("#")]
    assert body[0] == "delta,P,segment"
    data = np.array([[float(v) for v in line.split(",")] for line in body[1:]])
    return data[:, 0], data[:, 1], data[:, 2].astype(int)


def test_fit_equals_cli(cli, source, tmp_path):
    delta, P, segment = load_sample(source)
    r = layerjkr.fit(delta, P, str(source / SCENE), free=["E", "w", "delta0", "P0"], segment=segment, branch="all")
    out = tmp_path / "report.json"
    run_cli(cli, source, "fit", "data/curves/hydrogel_film_two_term.csv", "--scene", SCENE, "--free", "E,w,delta0,P0",
            "--branch", "all", "--out", str(out))
    ref = json.loads(out.read_text())
    made_from = ref.pop("provenance")
    assert r.as_dict() == ref
    assert list(r.as_dict()) == list(ref)
    # The same keywords are the same options, and the same scene, as the CLI records them.
    assert r.provenance["options"] == made_from["options"]
    for key in ("json", "sha256", "description"):  # "file": the path as given, relative for the CLI here
        assert r.provenance["scene"][key] == made_from["scene"][key], key
    assert r.parameters == tuple(ref["parameters"]) == ("E", "w", "delta0", "P0")
    for name, p in ref["parameters"].items():
        assert r.values[name] == p["value"], name
        assert r.errors[name] == p["stderr"], name
        for other, c in ref["correlation"][name].items():
            assert r.correlation[name, other] == c, (name, other)
    assert r.converged and r.identifiable
    assert r.P_fit.shape == r.P.shape == r.delta.shape == r.excluded.shape
    assert np.array_equal(r.residuals, r.P - r.P_fit)
    assert "E" in r.report() and r.report().startswith("layerjkr fit: converged")


def test_fit_uncertainty_arrays_by_name(source):
    delta, P, segment = load_sample(source)
    r = layerjkr.fit(delta, P, str(source / SCENE), free="E,w,delta0,P0", segment=segment, branch="all")
    c, cov, err = r.correlation, r.covariance, r.errors
    assert c.shape == cov.shape == (4, 4) and err.shape == r.values.shape == (4,)
    assert c["E", "w"] == c["w", "E"] == c[0, 1] and np.array_equal(c, c.T)
    assert np.array_equal(np.diag(c), np.ones(4))
    assert np.array_equal(c["E"], c[0]) and type(c["E"]) is np.ndarray
    assert np.array_equal(np.diag(cov), err ** 2) and np.array_equal(cov, cov.T)
    assert cov["E", "w"] == pytest.approx(c["E", "w"] * err["E"] * err["w"], rel=1e-15)
    assert r.values.names == r.parameters and r.values.to_dict()["E"] == r.values["E"]
    assert c.to_dict()["w"]["E"] == c["w", "E"]
    with pytest.raises(KeyError, match="'K' is not a fitted parameter"):
        r.values["K"]
    with pytest.raises(ValueError):
        r.values[0] = 1.0  # read-only
    back = pickle.loads(pickle.dumps(r))  # Dask moves results between processes
    assert back.as_dict() == r.as_dict() and np.array_equal(back.P_fit, r.P_fit)
    assert back.provenance == r.provenance
    named = pickle.loads(pickle.dumps(c))
    assert named["E", "w"] == c["E", "w"] and named.names == c.names


def test_options_are_typed_keywords(source):
    delta, P, segment = load_sample(source)
    scene = layerjkr.scene(str(source / SCENE))
    with pytest.raises(TypeError, match="brunch"):
        layerjkr.fit(delta, P, scene, free="E,w", brunch="all")
    with pytest.raises(TypeError):
        layerjkr.fit(delta, P, scene, ["E", "w"])  # free is keyword-only
    with pytest.raises(TypeError, match="threshold"):
        layerjkr.curve(scene, [1e-6], threshold=0.1)
    with pytest.raises(TypeError, match="jobz"):
        layerjkr.fit_batch([(delta, P)], scene, jobz=2)
    with pytest.raises(TypeError, match="unit"):
        layerjkr.fit_files([], scene, unit="nm,nN")
    for keyword, bad in [("branch", "sideways"), ("control", "spring"), ("baseline", "slope"), ("window", "half"),
                         ("loss", "l1")]:
        for call in (layerjkr.fit, lambda *a, **k: layerjkr.fit_batch([a[:2]], a[2], **k)):
            with pytest.raises(layerjkr.InputError, match='^%s = "%s" is unknown' % (keyword, bad)):
                call(delta, P, scene, **{keyword: bad})
    with pytest.raises(layerjkr.InputError, match='^free = "colour" is unknown'):
        layerjkr.fit(delta, P, scene, free="E,colour")
    with pytest.raises(layerjkr.DomainError, match="loss_scale"):
        layerjkr.fit(delta, P, scene, loss="huber")
    with pytest.raises(layerjkr.InputError, match="cantilever"):
        layerjkr.fit(delta, P, scene, branch="retract", control="cantilever")
    with pytest.raises(layerjkr.InputError, match="jobs = 0"):
        layerjkr.fit_batch([(delta, P)], scene, jobs=0)
    r = layerjkr.fit(delta, P, scene, segment=segment, branch="retract", loss="huber", loss_scale=1e-9,
                     window="fraction", window_fraction=0.8, control="cantilever", spring_constant=0.05)
    assert r.parameters == ("E", "w", "delta0", "P0") and r.as_dict()["branch"] == "retract"


def test_version_is_the_cmake_project_version(source):
    cmake = (source / "CMakeLists.txt").read_text()
    version = re.search(r"project\(\s*layerjkr\s+VERSION\s+([0-9.]+)", cmake).group(1)
    assert layerjkr.__version__ == layerjkr._core.__version__ == version


def test_dtypes_shapes_and_contiguity(source):
    scene = layerjkr.scene(str(source / SCENE))
    a64 = np.linspace(1e-7, 1e-6, 10)
    ref = layerjkr.curve(scene, a64).P
    strided = np.repeat(a64, 2)[::2]
    assert not strided.flags["C_CONTIGUOUS"] or strided.base is not None
    assert np.array_equal(layerjkr.curve(scene, strided).P, ref)
    assert np.array_equal(layerjkr.curve(scene, list(a64)).P, ref)
    a32 = a64.astype(np.float32)
    assert np.array_equal(layerjkr.curve(scene, a32).P, layerjkr.curve(scene, a32.astype(np.float64)).P)
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
    with pytest.raises(layerjkr.DomainError, match="warning_threshold"):
        layerjkr.summary(scene, warning_threshold=1.5)
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
    worker = threading.Thread(target=lambda: (layerjkr.fit_batch(curves, scene, free=["E", "w", "delta0"], jobs=1),
                                              done.set()))
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
    serial = layerjkr.fit_batch(curves, scene, free="E,w,delta0", jobs=1)
    threaded = layerjkr.fit_batch(curves, scene, free="E,w,delta0", jobs=2)
    assert [s.result.as_dict() for s in serial] == [t.result.as_dict() for t in threaded]
    assert all(s.ok and s.error is None and s.curve is None for s in serial)
    assert [s.source for s in serial] == ["curve %d" % k for k in range(4)]
    with pytest.warns(layerjkr.ModelWarning, match="on approach the model snaps in at zero load") as record:
        single = layerjkr.fit(delta, P * (1 + 1e-3), scene, free="E,w,delta0")
    assert [str(w.message) for w in record] == single.warnings == serial[1].result.warnings  # the batch: not emitted
    assert single.values.to_dict() == serial[1].result.values.to_dict()
    failed = layerjkr.fit_batch([(delta[:2], P[:2])], scene)
    assert not failed[0].ok and failed[0].result is None and "curve 0" in failed[0].error


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
        assert np.max(np.abs(c.P / truth.P - 1)) < 1e-6
        assert s.profile.startswith("table(201 points")
    with pytest.raises(layerjkr.InputError, match="r_max"):
        layerjkr.scene(spec, profile=lambda r: r * r)
    with pytest.raises(layerjkr.InputError, match="non-finite"):
        layerjkr.scene(spec, profile=lambda r: np.log(r), r_max=1e-6)
    with pytest.raises(layerjkr.Error):
        layerjkr.scene(spec, profile=lambda r: -r, r_max=1e-6)  # not an indenter: falls away


_LONG_BATCH = r"""
import sys, time, layerjkr
curve, scene, kind = sys.argv[1:4]
paths = [curve] * 400  # 400 fits with 20 extra starts each: several seconds of work
print("started", flush=True)
try:
    if kind == "files":
        layerjkr.fit_files(paths, scene, free="E,w,delta0,P0", branch="all", starts=20, jobs=2)
    else:
        import numpy as np
        body = [line for line in open(curve).read().splitlines() if not line.startswith("#")][1:]
        data = np.array([[float(v) for v in line.split(",")] for line in body])
        layerjkr.fit_batch([(data[:, 0], data[:, 1])] * 400, scene, free="E,w,delta0,P0", branch="all",
                           starts=20, jobs=2)
    print("finished uninterrupted", flush=True)
except KeyboardInterrupt as e:
    caught = time.monotonic()
    print("interrupted", len(e.results), all(r.ok for r in e.results), caught, flush=True)
"""


@pytest.mark.parametrize("kind", ["files", "arrays"])
def test_ctrl_c_stops_a_batch_and_keeps_its_results(source, kind):
    # SIGINT to a process running a long batch: KeyboardInterrupt soon after, not after the
    # batch, with the finished fits (a prefix) attached. The delay is printed, not asserted.
    import signal
    import sys
    import time
    p = subprocess.Popen([sys.executable, "-c", _LONG_BATCH, str(source / "data/curves/hydrogel_film_two_term.csv"),
                          str(source / SCENE), kind], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline() == "started\n"
    # 3 s: the first fits must have finished even on a loaded machine (1 s once left none done
    # while other builds ran); the whole batch takes about 40 s.
    time.sleep(3.0)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=120)
    words = out.split()
    assert words[0] == "interrupted", out
    assert 0 < int(words[1]) < 400
    assert words[2] == "True"
    print("KeyboardInterrupt %.3f s after SIGINT, %s fits kept" % (float(words[3]) - sent, words[1]))


def test_no_adhesion_reports_w_at_its_bound_with_an_upper_bound_and_the_reasons():
    # A Hertz retract without adhesion (closed form, 1e-7 N noise): before #23, w stopped at
    # ~1e-18 J/m^2 with every error bar NaN and identifiable True. Noise alone makes about half of
    # the realisations favour a small interior w (with its error bar); the first realisation
    # that ends at the bound is checked.
    E, R, nu = 1e6, 1e-5, 0.5
    d = np.linspace(1e-6, -0.5e-6, 500)
    scene = {"indenter": {"shape": "paraboloid", "R": R}, "medium": {"type": "half_space", "E": E, "nu": nu}}
    for seed in range(1, 21):
        rng = np.random.default_rng(seed)
        P = 4.0 / 3.0 * E / (1 - nu**2) * np.sqrt(R) * np.clip(d, 0, None)**1.5 + rng.normal(0, 1e-7, d.size)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            r = layerjkr.fit(d, P, scene, free="E,w,delta0,P0", segment=np.ones(d.size, dtype=int), branch="retract")
        assert all(np.isfinite(r.errors[k]) for k in ("E", "delta0", "P0"))
        if not r.at_bound["w"]:
            assert np.isfinite(r.errors["w"]) and r.identifiable and np.isnan(r.upper_bound["w"])
            continue
        assert any("w = 0 at its lower bound" in str(c.message) for c in caught)
        break
    assert r.at_bound["w"] and r.values["w"] == 0.0 and np.isnan(r.errors["w"])
    assert r.upper_bound["w"] > 0.0 and np.isnan(r.upper_bound["E"])
    assert abs(r.values["E"] - E) < 4 * r.errors["E"]
    assert r.identifiable and r.identifiability_known and r.identifiability_reason == ""
    assert "no adhesive signal" in r.reasons["w"] and r.reasons["E"] == ""
    d_ = r.as_dict()
    assert d_["parameters"]["w"]["upper_bound"] == r.upper_bound["w"] and d_["no_move_reason"] == r.no_move_reason


def test_goodness_of_fit_under_lmfits_names(source):
    # Issue 42: chisqr, redchi, aic, bic, ndata and nvarys as lmfit defines them, from the fit's
    # own residuals, kept through pickling.
    rows = [l.split(",") for l in (source / "data/curves/hydrogel_film_two_term.csv").read_text().splitlines()
            if l and l[0] not in "#d"]
    d, P, seg = (np.array([float(r[k]) for r in rows]) for k in range(3))
    r = layerjkr.fit(d, P, str(source / "data/scenes/hydrogel_film_two_term.json"), segment=seg, branch="all")
    chi = float(np.sum((r.P - r.P_fit) ** 2))
    n, k = r.ndata, r.nvarys
    assert (n, k) == (len(d), 4)
    assert r.chisqr == pytest.approx(chi, rel=1e-12)
    assert r.redchi == pytest.approx(chi / (n - k), rel=1e-12)
    assert r.aic == pytest.approx(n * np.log(chi / n) + 2 * k, rel=1e-12)
    assert r.bic == pytest.approx(n * np.log(chi / n) + k * np.log(n), rel=1e-12)
    assert r.rms_residual == pytest.approx(np.sqrt(chi / n), rel=1e-12)
    # nfev (issue 43): Ceres' residual and Jacobian evaluations, at least one per iteration and the start's.
    assert r.nfev >= r.iterations + 1 and r.as_dict()["statistics"]["function_evaluations"] == r.nfev
    again = pickle.loads(pickle.dumps(r))
    assert (again.aic, again.bic, again.ndata, again.nfev) == (r.aic, r.bic, r.ndata, r.nfev)
