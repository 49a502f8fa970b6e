"""layerjkr: adhesive (JKR) contact of thin elastic layers, from Python.

The same library as the ``layerjkr`` command line, with numpy in and out::

    import layerjkr
    s = layerjkr.scene("data/scenes/hydrogel_film_two_term.json")   # or a dict, same schema
    c = layerjkr.curve(s, np.linspace(1e-7, 2e-6, 200))           # dict of arrays, SI units
    layerjkr.summary(s)["pull_off_force"]                          # the CLI's summary keys
    r = layerjkr.fit(delta, P, scene=s, free=["E", "w", "delta0"], branch="retract")
    print(r.report())

Fit options are named as the CLI's flags (``branch``, ``loss``, ``control``, ``baseline``,
``window``, ``units``, ``starts``, ``max_iterations``, ``spring_constant``, ``curve``). Long
calls release the GIL, so threads run fits in parallel. Errors raise :class:`Error` and its
subclasses with the C++ library's messages.
"""
import json
import os

import numpy as np

from . import _core
from ._core import DomainError, Error, InputError, NumericalError, Scene

__all__ = ["Error", "DomainError", "InputError", "NumericalError", "Scene", "FitResult", "scene", "curve",
           "summary", "fit", "fit_batch", "fit_files", "read_instrument"]


def scene(spec, profile=None, r_max=None, samples=501):
    """A scene from a dict (the CLI's JSON schema), a JSON file path or a Scene.

    ``profile``: a Python callable f(r) -> height [m] (vectorised over a numpy array or not)
    that replaces the scene's indenter. It is sampled at ``samples`` radii on [0, r_max] and
    interpolated as a measured tip table (a C2 cubic spline, mirrored at r = 0): contact radii
    up to r_max are admissible. Accuracy: that of the spline, about (r_max / samples)^2 relative
    in f''; test your r_max and samples against a known profile (docs/python.md).
    """
    if isinstance(spec, Scene):
        s = spec
    elif isinstance(spec, dict):
        s = _core.parse_scene(json.dumps(spec), "scene dict")
    elif isinstance(spec, (str, os.PathLike)):
        s = _core.load_scene(os.fspath(spec))
    else:
        raise InputError("scene: expected a dict, a JSON file path or a layerjkr.Scene, got %s" % type(spec).__name__)
    if profile is None:
        return s
    if not callable(profile):
        raise InputError("scene: profile must be a callable f(r) -> height [m]")
    if r_max is None or not float(r_max) > 0 or not np.isfinite(r_max):
        raise InputError("scene: a callable profile needs r_max > 0 [m], the largest contact radius; got %r" % (r_max,))
    if int(samples) < 3:
        raise InputError("scene: samples = %r must be >= 3" % (samples,))
    r = np.linspace(0.0, float(r_max), int(samples))
    try:
        with np.errstate(all="ignore"):  # a non-finite height is reported below, by radius
            z = np.asarray(profile(r), dtype=np.float64)
        if z.shape != r.shape:
            raise ValueError
    except Exception:  # not vectorised: one radius at a time
        z = np.array([float(profile(x)) for x in r])
    if not np.all(np.isfinite(z)):
        raise InputError("scene: the profile callable returned a non-finite height at r = %r m" % r[~np.isfinite(z)][0])
    return _core.with_table_profile(s, r.tolist(), z.tolist())


# The fit functions take a parameter named scene, as the CLI's --scene; this reaches the function.
_as_scene = scene


def curve(scene_spec, a):
    """The adhesive curve at contact radii ``a`` [m]: a dict of float64 arrays a, P, delta, P_H,
    delta_H, S, dS_da, error_est (as ``layerjkr curve``), plus 'warnings' and 'note'."""
    return _core.curve(scene(scene_spec), np.asarray(a, dtype=np.float64))


def summary(scene_spec):
    """The keys of ``layerjkr summary``: pull-off, zero-load radius, fixed grips, model error."""
    return json.loads(_core.summary(scene(scene_spec)))


class FitResult:
    """A fit: estimates with standard errors, correlation, identifiability, warnings, and the
    data with the fitted curve (``delta``, ``P``, ``P_fit``, ``excluded``)."""

    def __init__(self, output):
        self._report = json.loads(output.report)
        self._brief = output.brief
        self.delta, self.P, self.P_fit, self.excluded = output.delta, output.P, output.P_fit, output.excluded

    @property
    def values(self):
        """{name: value} in SI units."""
        return {k: v["value"] for k, v in self._report["parameters"].items()}

    @property
    def stderr(self):
        """{name: standard error} (None where not identifiable)."""
        return {k: v["stderr"] for k, v in self._report["parameters"].items()}

    @property
    def correlation(self):
        return self._report["correlation"]

    @property
    def identifiable(self):
        return self._report["identifiable"]

    @property
    def warnings(self):
        return self._report["warnings"]

    @property
    def converged(self):
        return self._report["converged"]

    @property
    def residuals(self):
        return self.P - self.P_fit

    def as_dict(self):
        """The JSON keys of ``layerjkr fit --out``."""
        return dict(self._report)

    def report(self):
        """The brief report the CLI prints."""
        return self._brief

    def __repr__(self):
        return "FitResult(%s)" % ", ".join("%s=%.6g" % kv for kv in self.values.items())


def _free(free):
    if isinstance(free, str):
        free = free.split(",")
    return [str(f) for f in free]


def fit(delta, P, scene, free, segment=None, **options):
    """Fit one curve: ``delta`` [m] and ``P`` [N] 1-D arrays, ``segment`` optional 0/1 labels
    (approach/retract). Options as the CLI's flags. Returns a :class:`FitResult`."""
    seg = None if segment is None else [int(s) for s in np.asarray(segment).ravel()]
    out = _core.fit(np.asarray(delta, dtype=np.float64), np.asarray(P, dtype=np.float64), seg,
                    _as_scene(scene), _free(free), options)
    return FitResult(out)


def _items(items):
    for it in items:
        it["report"] = json.loads(it["report"]) if it["ok"] else None
    return items


def fit_batch(curves, scene, free, jobs=1, **options):
    """Fit many (delta, P) pairs on ``jobs`` threads; one dict per curve (ok, error, report)."""
    pairs = [(np.asarray(d, dtype=np.float64), np.asarray(p, dtype=np.float64)) for d, p in curves]
    return _items(_core.fit_batch(pairs, _as_scene(scene), _free(free), options, int(jobs)))


def fit_files(paths, scene, free, jobs=1, **options):
    """Fit CSV and instrument files (maps give one item per curve) on ``jobs`` threads, as
    ``layerjkr fit-map``; one dict per curve: source, curve, x, y, grid_x, grid_y, ok, error, report."""
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    return _items(_core.fit_files([os.fspath(p) for p in paths], _as_scene(scene), _free(free), options,
                                  int(jobs)))


def read_instrument(path):
    """The curves of a JPK (.jpk-force, -force-map, -qi-data) or Igor (.ibw) file: a list of
    dicts with delta (= -tip position) [m], P [N], segment, spring_constant, x, y, grid_x, grid_y."""
    return _core.read_instrument(os.fspath(path))
