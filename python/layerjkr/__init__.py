"""layerjkr: adhesive (JKR) contact of thin elastic layers, from Python.

The same library as the ``layerjkr`` command line, with numpy in and out::

    import numpy as np, layerjkr
    s = layerjkr.scene("data/scenes/hydrogel_film_two_term.json")  # or a dict, same schema
    c = layerjkr.curve(s, np.linspace(1e-7, 2e-6, 200))           # Curve: c.P, c.delta, ...
    layerjkr.summary(s).pull_off_force                             # or ["pull_off_force"]
    r = layerjkr.fit(delta, P, s, free=["E", "w", "delta0"], branch="retract")
    r.values["E"], r.errors["E"], r.correlation["E", "w"]
    print(r.report())

Every option is a keyword with its default in the signature; a misspelt keyword is a
``TypeError``, a misspelt choice an :class:`InputError` naming the parameter. Long calls
release the GIL, so threads run fits in parallel. Errors raise :class:`Error` and its
subclasses with the C++ library's messages; an answer the library warns about also emits a
:class:`ModelWarning` through :mod:`warnings`.
"""
from __future__ import annotations

import contextlib
import json
import math
import os
import sys
import tempfile
import warnings as _warnings
from typing import (Any, Callable, Dict, Iterator, List, Literal, NamedTuple, Optional, Sequence,
                    Tuple, Union, overload)

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import DomainError, Error, InputError, NumericalError, Scene

__version__: str = _core.__version__

__all__ = ["__version__", "Error", "DomainError", "InputError", "NumericalError", "ModelWarning", "Scene",
           "simulate", "Simulation", "fit_joint", "JointFitResult",
           "AutoChoice", "AdhesionCheck", "FixedGrips", "ModelError", "Curve", "Summary", "NamedArray", "FitResult", "BatchResult",
           "Instrument", "scene", "curve", "summary", "fit", "fit_batch", "fit_files", "read_instrument",
           "open_instrument"]

SceneLike = Union[Scene, Dict[str, Any], str, "os.PathLike[str]"]
Branch = Literal["approach", "retract", "all"]
Control = Literal["auto", "load", "cantilever", "grips"]
BaselineKind = Literal["constant", "tilt"]
Window = Literal["all", "pull_off", "fraction"]
Loss = Literal["none", "huber", "cauchy"]
ContactPointMethod = Literal["fit", "threshold", "rov", "gof"]
CurveRangeLike = Union[slice, Tuple[int, int]]


class ModelWarning(UserWarning):
    """An answer the library warns about: a model estimated to be off its reference by more
    than the warning threshold, or constants outside a model's validity. The same text is in
    the answer's ``warnings`` list."""


def _number(name: str, value: Any) -> float:
    """A real number for option ``name``, else TypeError naming it (not a bare conversion error)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError("%s must be a number, got %s %r" % (name, type(value).__name__, value))
    return float(value)


def _integer(name: str, value: Any) -> int:
    """An integer for option ``name``: 2.5 is refused rather than truncated."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError("%s must be an integer, got %s %r" % (name, type(value).__name__, value))
    return int(value)


def _text(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError("%s must be a string, got %s %r" % (name, type(value).__name__, value))
    return value


def _json_value(value: Any) -> Any:
    """numpy scalars and arrays in a scene dict as the JSON numbers and lists they hold."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError("scene: a value of type %s cannot be written as JSON" % type(value).__name__)


def _segments(segment: npt.ArrayLike) -> List[int]:
    """Segment labels 0, 1 or 2; a non-integer label (0.5) is refused with its value, not cast."""
    values = np.asarray(segment).ravel()
    out = []
    for i, v in enumerate(values.tolist()):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v != int(v):
            raise InputError("segment[%d] = %r is not a segment label; valid values: 0 (approach), 1 (retract), 2 (dwell)" % (i, v))
        out.append(int(v))
    return out


def _warn(messages: Sequence[str], stacklevel: int) -> None:
    for message in messages:
        _warnings.warn(message, ModelWarning, stacklevel=stacklevel + 1)


def scene(spec: SceneLike, profile: Optional[Callable[[Any], Any]] = None, r_max: Optional[float] = None,
          samples: int = 501) -> Scene:
    """A scene: indenter, medium, model and work of adhesion.

    Parameters
    ----------
    spec : dict, str, os.PathLike or Scene
        A dict with the keys of the CLI's scene JSON, the path of a scene file, or a Scene
        (returned as is unless ``profile`` is given).
    profile : callable, optional
        ``f(r) -> height`` [m], vectorised over a numpy array or not, replacing the scene's
        indenter. It is sampled at ``samples`` radii on [0, r_max] and interpolated as a
        measured tip table (a C2 cubic spline, mirrored at r = 0): contact radii up to
        ``r_max`` are admissible. Accuracy is the spline's, about (r_max / samples)^2 relative
        in f''; test r_max and samples against a known profile (docs/python.md).
    r_max : float, optional
        The largest contact radius [m]; required with ``profile``.
    samples : int, default 501
        Radii at which ``profile`` is sampled, >= 3.

    Returns
    -------
    Scene

    Raises
    ------
    InputError
        An unknown key, a wrong type or an invalid value in the scene (the message names
        it), a file that cannot be read, or an invalid ``profile``, ``r_max`` or ``samples``.
    """
    if isinstance(spec, Scene):
        s = spec
    elif isinstance(spec, dict):
        s = _core.parse_scene(json.dumps(spec, default=_json_value), "scene dict")
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
    if s.json:
        # The sampled profile as the scene's table indenter, parsed like any scene: the scene's
        # JSON keeps describing it, so a fit's provenance records it (json writes doubles exactly).
        spec_json = json.loads(s.json)
        spec_json["indenter"] = {"shape": "table", "r": r.tolist(), "z": z.tolist()}
        return _core.parse_scene(json.dumps(spec_json), "scene with a callable profile")
    return _core.with_table_profile(s, r.tolist(), z.tolist())


# The fit functions take a parameter named scene, as the CLI's --scene; this reaches the function.
_as_scene = scene


class AutoChoice(NamedTuple):
    """What model ``"auto"`` chose, and how well the choice was judged to do."""

    model: str
    """The chosen model."""
    estimated_error: float
    """The chosen model's worst estimated relative error where it was judged."""
    tolerance: float
    """The scene's target."""
    judged_at: str
    """Where it was judged, e.g. "over the curve's radii"."""
    note: str
    """One line: "auto chose model 'uniform' (estimated error 0.003 over the curve's radii)"."""


def _choice(c: Any) -> Optional[AutoChoice]:
    if c is None:
        return None
    return AutoChoice(c.model, c.estimated_error, c.tolerance, c.judged_at, c.brief_report())


class FixedGrips(NamedTuple):
    """The fixed-grips (displacement-controlled) critical point."""

    force: float
    """P [N]."""
    radius: float
    """a [m]."""
    delta: float
    """Approach [m]."""


class AdhesionCheck(NamedTuple):
    """Whether the answer's adhesion model applies: Maugis' lambda of the contact and the
    estimated error of its pull-off force against Maugis-Dugdale (adhesion_check.hpp)."""

    lambda_: float
    """Maugis' lambda, from the contact's own compliance (``lambda`` in as_dict)."""
    sigma0: float
    """The Dugdale stress it was judged with [Pa]."""
    sigma0_assumed: bool
    """True when sigma0 comes from the assumed spacing z0 = 0.3 nm (none was given)."""
    pull_off_error: float
    """Estimated |P_model / P_MD - 1| of the pull-off force (0 for Maugis-Dugdale)."""
    basis: str
    """"closed form" or "half-space estimate"."""


class ModelError(NamedTuple):
    """Estimated relative model errors of a summary, against its reference model."""

    pull_off_force: float
    """|P* - P*_ref| / |P*_ref| (inf where the model misses a point its reference has)."""
    zero_load_radius: float
    """|a0 - a0_ref| / a0_ref."""
    reference: str
    """The reference model's name, or "none"."""


_CURVE_ROWS = ("a", "P", "delta", "P_H", "delta_H", "S", "dS_da", "error_estimate", "c")


class Curve:
    """A scene's adhesive curve at given contact radii (the library's CurveAnswer).

    Every array is float64, one value per radius in the order given, SI units. Index by name
    as well: ``c["P"]`` is ``c.P``.
    """

    __slots__ = ("_block", "_warnings", "_model", "_reference", "_choice", "_seconds", "_notices")

    def __init__(self, block: npt.NDArray[np.float64], warnings: List[str], model: str, reference: str,
                 choice: Optional[AutoChoice], seconds: float, notices: Sequence[str] = ()) -> None:
        self._block, self._warnings, self._model = block, warnings, model
        self._reference, self._choice, self._seconds = reference, choice, seconds
        self._notices = list(notices)

    @property
    def a(self) -> npt.NDArray[np.float64]:
        """Contact radius [m]."""
        return self._block[0]

    @property
    def P(self) -> npt.NDArray[np.float64]:
        """Adhesive force [N], negative = tensile."""
        return self._block[1]

    @property
    def delta(self) -> npt.NDArray[np.float64]:
        """Adhesive approach [m]."""
        return self._block[2]

    @property
    def P_H(self) -> npt.NDArray[np.float64]:
        """Non-adhesive (Hertz-like) force at the same radius [N]."""
        return self._block[3]

    @property
    def delta_H(self) -> npt.NDArray[np.float64]:
        """Non-adhesive approach at the same radius [m]."""
        return self._block[4]

    @property
    def S(self) -> npt.NDArray[np.float64]:
        """Contact stiffness dP_H/d delta_H [N/m]."""
        return self._block[5]

    @property
    def dS_da(self) -> npt.NDArray[np.float64]:
        """dS/da [N/m^2]."""
        return self._block[6]

    @property
    def error_estimate(self) -> npt.NDArray[np.float64]:
        """Estimated relative model error at each radius (0 where the model is exact)."""
        return self._block[7]

    @property
    def error_est(self) -> npt.NDArray[np.float64]:
        """Alias of :attr:`error_estimate` (the CLI's column name)."""
        return self._block[7]

    @property
    def c(self) -> npt.NDArray[np.float64]:
        """Outer radius of the adhesive zone [m]: a for JKR, beyond it for Maugis-Dugdale
        (the Dugdale zone's edge) and DMT (inf for the classical limit)."""
        return self._block[8]

    @property
    def warnings(self) -> List[str]:
        """The library's warnings (also emitted as :class:`ModelWarning`)."""
        return list(self._warnings)

    @property
    def notices(self) -> List[str]:
        """What the answer records but does not warn about (never a :class:`ModelWarning`): a
        documented approximation such as the pyramid's equivalent cone."""
        return list(self._notices)

    @property
    def model(self) -> str:
        """The model that answered."""
        return self._model

    @property
    def reference(self) -> str:
        """The model it was judged against, or "none"."""
        return self._reference

    @property
    def choice(self) -> Optional[AutoChoice]:
        """Model "auto": what it chose; else None."""
        return self._choice

    @property
    def seconds(self) -> float:
        """Wall time of the C++ answer [s]."""
        return self._seconds

    def __getitem__(self, name: str) -> Any:
        if name not in _CURVE_KEYS:
            raise KeyError("%r is not a key of a Curve (keys: %s)" % (name, ", ".join(_CURVE_KEYS)))
        return getattr(self, name)

    def keys(self) -> Tuple[str, ...]:
        """The names ``c[name]`` accepts."""
        return _CURVE_KEYS

    def as_dict(self) -> Dict[str, Any]:
        """The arrays and the metadata as a dict (keys as :meth:`keys`)."""
        return {k: getattr(self, k) for k in _CURVE_KEYS}

    def __len__(self) -> int:
        return int(self._block.shape[1])

    def __repr__(self) -> str:
        return "layerjkr.Curve(model=%r, %d radii, %d warnings)" % (self._model, len(self), len(self._warnings))


_CURVE_KEYS = _CURVE_ROWS + ("error_est", "warnings", "notices", "model", "reference", "choice")


def curve(scene: SceneLike, a: npt.ArrayLike, *, warning_threshold: float = 0.05) -> Curve:
    """The adhesive curve of a scene at contact radii ``a``.

    Parameters
    ----------
    scene : Scene, dict or path
        The scene (see :func:`scene`).
    a : array_like
        Contact radii [m], 1-D, each finite and > 0 (converted to float64).
    warning_threshold : float, default 0.05
        A curve whose estimated relative model error exceeds this, in (0, 1), carries a
        warning.

    Returns
    -------
    Curve
        a, P, delta, P_H, delta_H, S, dS_da, error_estimate as float64 arrays, with the
        warnings, the model, its reference and model "auto"'s choice. ``layerjkr curve``
        prints the same numbers.

    Raises
    ------
    InputError
        ``a`` not 1-D, or a radius not finite and > 0 (the message names it); an invalid scene.
    DomainError
        ``warning_threshold`` outside (0, 1).
    NumericalError
        A computation that could not reach its accuracy.

    Warns
    -----
    ModelWarning
        Each of the curve's warnings.
    """
    block, warnings, model, reference, choice, seconds, notices = _core.curve(
        _as_scene(scene), np.asarray(a, dtype=np.float64), _number("warning_threshold", warning_threshold))
    result = Curve(block, warnings, model, reference, _choice(choice), seconds, notices)
    _warn(warnings, 2)
    return result


class _SummaryFields(NamedTuple):  # the bound SummaryAnswer as plain (picklable) values
    model: str
    profile: str
    w: float
    pull_off: Optional[Tuple[float, float, float]]
    zero_load_radius: Optional[float]
    fixed_grips: Optional[Tuple[float, float, float]]
    error: Tuple[float, float, str]
    K: Optional[float]
    G: Optional[float]
    g_is_tension: bool
    E_star: Optional[float]
    adhesion_model: str
    adhesion: Optional[Tuple[float, float, bool, float, str]]
    warnings: List[str]
    notices: List[str]
    seconds: float
    kinetic: Optional[Dict[str, Any]]


class Summary:
    """A scene's summary (the library's SummaryAnswer): critical points, their estimated
    errors and the medium's constants, SI units.

    ``s[key]`` and :meth:`as_dict` use the keys of ``layerjkr summary``'s JSON, with the same
    values (None for a point the model does not have and for an unbounded error).
    """

    __slots__ = ("_a", "_choice")

    def __init__(self, answer: Any) -> None:
        self._a = _SummaryFields(*(getattr(answer, k) for k in _SummaryFields._fields))
        self._choice = _choice(answer.choice)

    @property
    def model(self) -> str:
        """The model that answered."""
        return self._a.model

    @property
    def profile(self) -> str:
        """The indenter, described."""
        return self._a.profile

    @property
    def w(self) -> float:
        """Work of adhesion [J/m^2]."""
        return self._a.w

    def _pull_off(self, k: int) -> Optional[float]:
        p = self._a.pull_off
        return None if p is None else p[k]

    @property
    def pull_off_force(self) -> Optional[float]:
        """Pull-off force under load control [N] (negative), or None."""
        return self._pull_off(1)

    @property
    def pull_off_radius(self) -> Optional[float]:
        """Contact radius at pull-off [m], or None."""
        return self._pull_off(0)

    @property
    def pull_off_delta(self) -> Optional[float]:
        """Approach at pull-off [m], or None."""
        return self._pull_off(2)

    @property
    def zero_load_radius(self) -> Optional[float]:
        """Contact radius at zero load [m], or None."""
        return self._a.zero_load_radius

    @property
    def fixed_grips(self) -> Optional[FixedGrips]:
        """The fixed-grips critical point, or None."""
        p = self._a.fixed_grips
        return None if p is None else FixedGrips(force=p[1], radius=p[0], delta=p[2])

    @property
    def model_error(self) -> ModelError:
        """Estimated relative errors of the pull-off force and the zero-load radius."""
        return ModelError(*self._a.error)

    @property
    def K(self) -> Optional[float]:
        """Foundation modulus [N/m^3] (a foundation's, or a layer's thin-layer constant), or None."""
        return self._a.K

    @property
    def G(self) -> Optional[float]:
        """Shear foundation constant [N/m], or None (also for a Filonenko-Borodich tension: see :attr:`T`)."""
        return None if self._a.g_is_tension else self._a.G

    @property
    def T(self) -> Optional[float]:
        """Filonenko-Borodich membrane tension [N/m], or None."""
        return self._a.G if self._a.g_is_tension else None

    @property
    def E_star(self) -> Optional[float]:
        """Plane-strain modulus [Pa] of a layer or the half-space, or None."""
        return self._a.E_star

    @property
    def choice(self) -> Optional[AutoChoice]:
        """Model "auto": what it chose; else None."""
        return self._choice

    @property
    def adhesion_model(self) -> str:
        """How adhesion acts in the answer: "jkr", "dmt" or "maugis_dugdale"."""
        return self._a.adhesion_model

    @property
    def adhesion(self) -> Optional[AdhesionCheck]:
        """Whether the adhesion model applies (lambda, its pull-off error), or None for w = 0."""
        c = self._a.adhesion
        return None if c is None else AdhesionCheck(*c)

    @property
    def warnings(self) -> List[str]:
        """The library's warnings (also emitted as :class:`ModelWarning`)."""
        return list(self._a.warnings)

    @property
    def notices(self) -> List[str]:
        """What the answer records but does not warn about (never a :class:`ModelWarning`)."""
        return list(self._a.notices)

    @property
    def seconds(self) -> float:
        """Wall time of the C++ answer [s]."""
        return self._a.seconds

    def as_dict(self) -> Dict[str, Any]:
        """The keys and values of ``layerjkr summary``'s JSON, in its order.

        Returns
        -------
        dict
            model, profile, w, adhesion_model, pull_off_force, pull_off_radius, pull_off_delta,
            zero_load_radius, fixed_grips_critical ({force, radius, delta} or None),
            model_error_estimate ({pull_off_force, zero_load_radius, reference}), K and G (or
            T) where known, E_star where known, adhesion_check ({lambda, sigma0, sigma0_assumed,
            pull_off_error, basis} or None), model_choice for model "auto", warnings, notices.
        """
        fg = self.fixed_grips
        err = self.model_error
        d: Dict[str, Any] = {
            "model": self.model, "profile": self.profile, "w": self.w,
            "adhesion_model": self.adhesion_model, "pull_off_force": self.pull_off_force, "pull_off_radius": self.pull_off_radius,
            "pull_off_delta": self.pull_off_delta, "zero_load_radius": self.zero_load_radius,
            "fixed_grips_critical": None if fg is None else fg._asdict(),
            "model_error_estimate": {"pull_off_force": _finite_or_none(err.pull_off_force),
                                     "zero_load_radius": _finite_or_none(err.zero_load_radius),
                                     "reference": err.reference},
        }
        if self._a.K is not None:
            d["K"] = self._a.K
            d["T" if self._a.g_is_tension else "G"] = self._a.G if self._a.G is not None else 0.0
        if self._a.E_star is not None:
            d["E_star"] = self._a.E_star
        c = self.adhesion
        d["adhesion_check"] = None if c is None else {
            "lambda": c.lambda_, "sigma0": c.sigma0, "sigma0_assumed": c.sigma0_assumed,
            "pull_off_error": c.pull_off_error, "basis": c.basis}
        if self._choice is not None:
            d["model_choice"] = {"model": self._choice.model, "estimated_error": self._choice.estimated_error,
                                 "tolerance": self._choice.tolerance}
        k = self._a.kinetic
        if k is not None:
            d["kinetic_pull_off"] = {
                "drive": k["drive"], "control": k["control"], "rate": k["rate"], "rate_unit": k["rate_unit"],
                "start_force": k["start_force"], "pull_off_force": k["pull_off_force"],
                "pull_off": dict(zip(("a", "P", "delta"), k["pull_off"])), "pull_off_time": k["pull_off_time"],
                "separation_time": k["separation_time"], "equilibrium_pull_off_force": k["equilibrium_pull_off_force"],
                "equilibrium_separation": dict(zip(("a", "P", "delta"), k["equilibrium_separation"])),
                "rate_dependence": [{"rate": float(r), "pull_off_force": float(f)}
                                    for r, f in zip(k["rates"], k["pull_off_forces"])]}
        d["warnings"] = self.warnings
        d["notices"] = self.notices
        return d

    @property
    def kinetic(self) -> Optional[Dict[str, Any]]:
        """With adhesion kinetics and a retract rate: the rate-dependent pull-off (``layerjkr
        summary --retract-speed``'s ``kinetic_pull_off``), else None."""
        d = self.as_dict()
        return d.get("kinetic_pull_off")

    def __getitem__(self, key: str) -> Any:
        d = self.as_dict()
        if key not in d:
            raise KeyError("%r is not a key of this summary (keys: %s)" % (key, ", ".join(d)))
        return d[key]

    def keys(self) -> List[str]:
        """The keys of :meth:`as_dict`."""
        return list(self.as_dict())

    def __repr__(self) -> str:
        return "layerjkr.Summary(model=%r, pull_off_force=%r, zero_load_radius=%r)" % (
            self.model, self.pull_off_force, self.zero_load_radius)


def _finite_or_none(x: Optional[float]) -> Optional[float]:
    return x if x is not None and np.isfinite(x) else None


def summary(scene: SceneLike, *, warning_threshold: float = 0.05, retract_speed: Optional[float] = None,
            load_rate: Optional[float] = None, stiffness: Optional[float] = None, start_force: float = 0.0) -> Summary:
    """The summary of a scene: pull-off, zero-load radius, fixed grips, model error, constants.

    Parameters
    ----------
    scene : Scene, dict or path
        The scene (see :func:`scene`).
    warning_threshold : float, default 0.05
        A summary whose estimated relative model error exceeds this, in (0, 1), carries a
        warning.
    retract_speed : float, optional
        With adhesion kinetics in the scene: a retract at this speed [m/s] under fixed grips (or,
        with ``stiffness``, of a cantilever's base) gives the rate-dependent pull-off and its
        dependence on the speed (:attr:`Summary.kinetic`).
    load_rate : float, optional
        Instead of ``retract_speed``: a load-controlled retract at this rate [N/s].
    stiffness : float, optional
        The cantilever's stiffness [N/m] (with ``retract_speed``).
    start_force : float, default 0
        The retract starts from the equilibrium contact at this force [N].

    Returns
    -------
    Summary
        Its :meth:`Summary.as_dict` is ``layerjkr summary``'s JSON.

    Raises
    ------
    InputError
        An invalid scene.
    DomainError
        ``warning_threshold`` outside (0, 1).
    NumericalError
        A critical-point search that fails.

    Warns
    -----
    ModelWarning
        Each of the summary's warnings.
    """
    if retract_speed is not None and load_rate is not None:
        raise InputError("give retract_speed or load_rate, not both")
    if stiffness is not None and retract_speed is None:
        raise InputError("stiffness is a cantilever's: give it with retract_speed")
    control = None if retract_speed is None and load_rate is None else (
        "load" if load_rate is not None else "cantilever" if stiffness is not None else "grips")
    rate = load_rate if load_rate is not None else retract_speed
    result = Summary(_core.summary(_as_scene(scene), _number("warning_threshold", warning_threshold), control,
                                   0.0 if rate is None else _number("retract_speed" if load_rate is None else "load_rate", rate),
                                   0.0 if stiffness is None else _number("stiffness", stiffness),
                                   _number("start_force", start_force)))
    _warn(result._a.warnings, 2)
    return result


class NamedArray(np.ndarray):
    """A read-only float64 array of fit quantities indexed by parameter name as well as by
    position (iminuit's util pattern): ``values["E"]``, ``correlation["E", "w"]``,
    ``correlation["E"]`` (a row). Arithmetic gives plain arrays of the same shape."""

    _names: Tuple[str, ...]

    def __new__(cls, data: npt.ArrayLike, names: Sequence[str]) -> "NamedArray":
        obj = np.array(data, dtype=np.float64).view(cls)
        obj._names = tuple(names)
        obj.flags.writeable = False
        return obj

    def __array_finalize__(self, obj: Any) -> None:
        self._names = getattr(obj, "_names", ())

    @property
    def names(self) -> Tuple[str, ...]:
        """The parameter names, in index order."""
        return self._names

    def _index(self, key: Any) -> Any:
        if isinstance(key, str):
            try:
                return self._names.index(key)
            except ValueError:
                raise KeyError("%r is not a fitted parameter (fitted: %s)" % (key, ", ".join(self._names))) from None
        if isinstance(key, tuple):
            return tuple(self._index(k) for k in key)
        return key

    def __getitem__(self, key: Any) -> Any:
        out = super().__getitem__(self._index(key))
        return out.view(np.ndarray) if isinstance(out, np.ndarray) else out

    def to_dict(self) -> Dict[str, Any]:
        """{name: value} (1-D) or {name: {name: value}} (2-D), as Python floats."""
        if self.ndim == 1:
            return {n: float(v) for n, v in zip(self._names, self.view(np.ndarray))}
        m = self.view(np.ndarray)
        return {a: {b: float(m[i, k]) for k, b in enumerate(self._names)} for i, a in enumerate(self._names)}

    def __array_wrap__(self, out: Any, context: Any = None, *args: Any) -> Any:
        return np.asarray(out).view(np.ndarray) if out.ndim else out[()]

    def __reduce__(self) -> Any:
        return (NamedArray, (self.view(np.ndarray), self._names))

    def __repr__(self) -> str:
        if self.ndim == 1:
            return "NamedArray({%s})" % ", ".join("%r: %r" % (n, float(v)) for n, v in zip(self._names, self.view(np.ndarray)))
        return "NamedArray(%s, names=%r)" % (np.array2string(self.view(np.ndarray), separator=", "), self._names)


class _Parameter(NamedTuple):
    value: float
    standard_error: float
    initial: float
    at_bound: bool
    identifiable: bool
    upper_bound: float
    reason: str


class FitResult:
    """A fitted curve (the library's FitSummary): estimates with standard errors, their
    covariance and correlation, identifiability, warnings, and the data with the fitted curve.

    ``values``, ``errors``, ``covariance`` and ``correlation`` are :class:`NamedArray`
    indexed by the names in ``parameters``; ``provenance`` says what the fit was made from
    (version, scene, options, the inputs' SHA-256). Picklable (plain Python and numpy values).
    """

    __slots__ = ("_fields", "_params", "_corr", "_delta", "_P", "_P_fit", "_excluded", "_brief", "_branch",
                 "_provenance", "_t")

    def __init__(self, s: Any, branch: str, provenance: Optional[Dict[str, Any]] = None) -> None:
        self._fields = {k: getattr(s, k) for k in ("converged", "termination", "iterations", "model", "family",
                                                     "rms_residual", "excluded_count", "pull_off_force",
                                                     "baseline_slope", "baseline_slope_stderr", "baseline_offset",
                                                     "points",
                                                     "points_in_contact", "identifiable", "identifiability_known",
                                                     "identifiability_reason", "unidentifiable", "no_move_reason",
                                                     "warnings", "notices", "initial_cost", "final_cost",
                                                     "solve_seconds", "contact_point", "noise", "runs_z",
                                                     "residual_structure", "force_noise", "radius_noise",
                                                     "force_noise_given", "radius_noise_given")}
        self._params = {p.name: _Parameter(p.value, p.standard_error, p.initial, p.at_bound, p.identifiable,
                                              p.upper_bound, p.reason)
                        for p in s.parameters}
        self._corr = s.correlation
        self._delta, self._P, self._P_fit, self._excluded = s.delta, s.P, s.P_fit, s.excluded
        self._t = s.t
        self._brief = s.brief_report()
        self._branch = branch
        self._provenance = provenance if provenance is not None else {}

    def __getstate__(self) -> Any:
        return {k: getattr(self, k) for k in self.__slots__}

    def __setstate__(self, state: Any) -> None:
        for k, v in state.items():
            object.__setattr__(self, k, v)

    @property
    def delta(self) -> npt.NDArray[np.float64]:
        """The fitted branch's approach samples [m], in acquisition order (empty in a batch)."""
        return self._delta

    @property
    def P(self) -> npt.NDArray[np.float64]:
        """The fitted branch's force samples [N] (empty in a batch)."""
        return self._P

    @property
    def t(self) -> npt.NDArray[np.float64]:
        """A fit in time: each sample's time [s] (aligned with ``delta``); empty otherwise."""
        return getattr(self, "_t", np.empty(0))

    @property
    def P_fit(self) -> npt.NDArray[np.float64]:
        """The fitted model at the same samples [N] (empty in a batch)."""
        return self._P_fit

    @property
    def excluded(self) -> npt.NDArray[np.bool_]:
        """Per sample: a retract sample after the model's jump that is not JKR, excluded from
        the fit (empty in a batch)."""
        return self._excluded

    @property
    def parameters(self) -> Tuple[str, ...]:
        """The free parameters' names, in the order of ``free``."""
        return tuple(self._params)

    @property
    def values(self) -> NamedArray:
        """Fitted values, SI units."""
        return NamedArray([p.value for p in self._params.values()], self.parameters)

    @property
    def errors(self) -> NamedArray:
        """Standard errors scaled by the residual variance; NaN where not identifiable, at a
        bound or not computed."""
        return NamedArray([p.standard_error for p in self._params.values()], self.parameters)

    @property
    def correlation(self) -> NamedArray:
        """Correlation matrix of the estimates (symmetric; NaN where not computed)."""
        return NamedArray(self._corr, self.parameters)

    @property
    def covariance(self) -> NamedArray:
        """Covariance matrix of the estimates, SI units: ``correlation * outer(errors, errors)``
        (the library reports standard errors and correlations; as every map from the fit's
        internal parameters to SI is increasing, this is the linearised covariance exactly).
        Its diagonal is ``errors ** 2``; NaN where an error is."""
        e = np.array([p.standard_error for p in self._params.values()])
        c = np.array(self._corr) * np.outer(e, e)
        np.fill_diagonal(c, e * e)
        return NamedArray(c, self.parameters)

    @property
    def initial(self) -> NamedArray:
        """The data-driven starting values."""
        return NamedArray([p.initial for p in self._params.values()], self.parameters)

    @property
    def at_bound(self) -> Dict[str, bool]:
        """Per parameter: ended at its bound (w = 0; its error bar is one-sided)."""
        return {k: p.at_bound for k, p in self._params.items()}

    @property
    def upper_bound(self) -> Dict[str, float]:
        """Per parameter: for w at its bound, its 95 % one-sided upper bound [J/m^2] from the
        profile likelihood; NaN otherwise."""
        return {k: p.upper_bound for k, p in self._params.items()}

    @property
    def identifiable(self) -> bool:
        """True only when every parameter was shown identifiable (an error bar, or w's upper
        bound, was computed). False if the data cannot separate some parameters (see
        :attr:`unidentifiable`) or if that is unknown (:attr:`identifiability_known` is False);
        :attr:`identifiability_reason` says which and why."""
        return self._fields["identifiable"]

    @property
    def identifiability_known(self) -> bool:
        """False when identifiability could not be decided (the covariance failed or was not
        computed)."""
        return self._fields["identifiability_known"]

    @property
    def identifiability_reason(self) -> str:
        """Why the fit is not identifiable, or why that is unknown; empty when identifiable."""
        return self._fields["identifiability_reason"]

    @property
    def reasons(self) -> Dict[str, str]:
        """Per parameter: why it has no error bar or is not identifiable (empty when it has both)."""
        return {k: p.reason for k, p in self._params.items()}

    @property
    def no_move_reason(self) -> str:
        """Why the solver did not move from its start (empty when it did)."""
        return self._fields["no_move_reason"]

    @property
    def unidentifiable(self) -> List[str]:
        """The groups of parameters the data cannot separate."""
        return list(self._fields["unidentifiable"])

    @property
    def converged(self) -> bool:
        """Whether the solver converged."""
        return self._fields["converged"]

    @property
    def warnings(self) -> List[str]:
        """The fit's warnings (also emitted as :class:`ModelWarning` by :func:`fit`)."""
        return list(self._fields["warnings"])

    @property
    def notices(self) -> List[str]:
        """What the fit records but does not warn about (never a :class:`ModelWarning`): a
        numerical error far below what matters, a documented approximation, a reader's choice."""
        return list(self._fields["notices"])

    @property
    def model(self) -> str:
        """The contact model that was fitted."""
        return self._fields["model"]

    @property
    def family(self) -> str:
        """How the model was evaluated: "foundation", "hertz", "tabulated" or "dugdale"
        (a Dugdale law solved on the medium per parameter vector; docs/fitting.md)."""
        return self._fields["family"]

    @property
    def iterations(self) -> int:
        """Solver iterations."""
        return self._fields["iterations"]

    @property
    def termination(self) -> str:
        """The solver's termination message."""
        return self._fields["termination"]

    @property
    def rms_residual(self) -> float:
        """Root-mean-square force residual [N]."""
        return self._fields["rms_residual"]

    @property
    def contact_point(self) -> Dict[str, Any]:
        """The contact point the fit used: ``method``; ``value`` [m] (the fitted delta0 for
        "fit", else the method's point) and ``stderr`` [m] (delta0's standard error, or the
        method's uncertainty; NaN when delta0 was fixed with "fit"); ``baseline`` [N] the
        method found (NaN for "fit"); ``range_reference`` [m], the point the ranges were
        measured from (NaN without a range); ``approach_samples`` and ``samples_in_range``."""
        return dict(self._fields["contact_point"])

    @property
    def residuals(self) -> npt.NDArray[np.float64]:
        """``P - P_fit`` [N]."""
        return self.P - self.P_fit

    def report(self) -> str:
        """The brief report the CLI prints (FitSummary::brief_report)."""
        return self._brief

    @property
    def provenance(self) -> Dict[str, Any]:
        """What the fit was made from, as ``layerjkr fit --out`` records it (docs/provenance.md):
        ``layerjkr_version``; ``scene`` (its JSON as parsed, its file and that file's SHA-256, or
        for a scene built in code a description and a note); ``options`` (every FitOptions field);
        ``csv`` (every CsvOptions field; files only); ``inputs``, each with ``path``, ``size``
        [bytes] and ``sha256``: a file's bytes, or for arrays given directly the bytes of the
        float64 arrays the library fitted (``"delta (float64 array)"``, ``"P (float64 array)"``,
        ``"segment (int64 array)"``: native little-endian, C order, so
        ``hashlib.sha256(np.ascontiguousarray(delta, dtype=np.float64).tobytes())`` gives it).
        The nested dicts of a batch's results are shared between them: do not change them."""
        return self._provenance

    def as_dict(self) -> Dict[str, Any]:
        """The keys and values of ``layerjkr fit --out``'s JSON report, in its order (None for
        NaN), but its provenance (see :attr:`provenance`)."""
        f = self._fields
        names = self.parameters
        corr = np.asarray(self._corr)
        return {
            "converged": f["converged"], "termination": f["termination"], "iterations": f["iterations"],
            "model": f["model"], "family": f["family"], "branch": self._branch,
            "parameters": {k: {"value": p.value, "unit": _core.unit_of(k.split("[")[0]), "stderr": _finite_or_none(p.standard_error),
                               "initial": p.initial,
                               "at_bound": p.at_bound, "upper_bound": _finite_or_none(p.upper_bound),
                               "identifiable": p.identifiable, "reason": p.reason}
                           for k, p in self._params.items()},
            "correlation": {a: {b: _finite_or_none(float(corr[i, k])) for k, b in enumerate(names)}
                            for i, a in enumerate(names)},
            "rms_residual": f["rms_residual"], "excluded": f["excluded_count"],
            "pull_off_force": _finite_or_none(f["pull_off_force"]), "baseline_slope": f["baseline_slope"],
            "baseline_slope_stderr": f["baseline_slope_stderr"], "baseline_offset": f["baseline_offset"],
            "points": f["points"],
            "points_in_contact": f["points_in_contact"], "identifiable": f["identifiable"],
            "identifiability_known": f["identifiability_known"],
            "identifiability_reason": f["identifiability_reason"],
            "unidentifiable": list(f["unidentifiable"]), "no_move_reason": f["no_move_reason"],
            "warnings": list(f["warnings"]), "notices": list(f["notices"]),
            "noise": None if not math.isfinite(f["radius_noise"]) else {
                "P": f["force_noise"], "P_given": f["force_noise_given"], "a": f["radius_noise"],
                "a_given": f["radius_noise_given"]},
            "contact_point": {k: _finite_or_none(v) if isinstance(v, float) else v
                              for k, v in f["contact_point"].items()},
        }

    def __repr__(self) -> str:
        return "layerjkr.FitResult(%s)" % ", ".join(
            "%s=%.6g+-%.2g" % (k, p.value, p.standard_error) for k, p in self._params.items())


class BatchResult(NamedTuple):
    """One curve of :func:`fit_batch` or :func:`fit_files`: its fit, or why it failed."""

    source: str
    """The file name, or "curve N" in a batch of arrays."""
    curve: Optional[int]
    """The curve's number in an instrument file, else None."""
    x: float
    """Map position [m] (NaN where the file has none)."""
    y: float
    """Map position [m] (NaN where the file has none)."""
    grid_x: Optional[int]
    """Grid pixel (None where the file has none)."""
    grid_y: Optional[int]
    """Grid pixel (None where the file has none)."""
    result: Optional[FitResult]
    """The fit (without the per-sample arrays), or None if it failed."""
    error: Optional[str]
    """The library's message if the curve could not be read or fitted, else None."""

    @property
    def ok(self) -> bool:
        """True if the curve was fitted."""
        return self.result is not None


def _free(free: Union[str, Sequence[str]]) -> List[str]:
    if isinstance(free, str):
        free = free.split(",")
    return [_text("free", f) for f in free]


def _options(free: Union[str, Sequence[str]], branch: str, control: str, spring_constant: Optional[float],
             baseline: str, window: str, window_fraction: float, loss: str, loss_scale: Optional[float], starts: int,
             max_iterations: int, contact_point: str = "fit",
             indentation_range: Optional[Tuple[float, float]] = None, force_range: Optional[Tuple[float, float]] = None,
             baseline_window: Optional[Tuple[float, float]] = None) -> Any:
    return _core.fit_options(free=_free(free), branch=_text("branch", branch), control=_text("control", control),
                             spring_constant=None if spring_constant is None else _number("spring_constant", spring_constant),
                             baseline=_text("baseline", baseline), window=_text("window", window),
                             window_fraction=_number("window_fraction", window_fraction), loss=_text("loss", loss),
                             loss_scale=None if loss_scale is None else _number("loss_scale", loss_scale),
                             starts=_integer("starts", starts), max_iterations=_integer("max_iterations", max_iterations),
                             contact_point=_text("contact_point", contact_point),
                             indentation_range=_range("indentation_range", indentation_range),
                             force_range=_range("force_range", force_range),
                             baseline_window=_range("baseline_window", baseline_window))


def _range(name: str, value: Optional[Tuple[float, float]]) -> Optional[Tuple[float, float]]:
    if value is None:
        return None
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise InputError("%s = %r is invalid; give (min, max) or None" % (name, value))
    return (_number(name, value[0]), _number(name, value[1]))


_FIT_PARAMETERS_DOC = """
    free : sequence of str or str, default ("E", "w", "delta0")
        Parameters to identify: K, G (or T), w, delta0, P0, E, R, sigma0, and in time E_inf, tau
        (a standard linear solid), beta (a power law), v_star, n (crack kinetics); a
        comma-separated string is accepted too. The others come from the scene (delta0 = P0 = 0
        unless freed).
    branch : {"approach", "retract", "all"}, default "approach"
        Which part of the curve to fit.
    control : {"auto", "load", "cantilever", "grips"}, default "auto"
        What controls the retract: a cantilever where its stiffness is known (auto), load
        control, a cantilever of known stiffness, or fixed grips.
    spring_constant : float, optional
        The cantilever's stiffness [N/m], finite and > 0; None: the curve's own (instrument
        files), else unknown.
    baseline : {"constant", "tilt"}, default "constant"
        Subtract P0, or also a linear tilt fitted to the samples off contact.
    window : {"all", "pull_off", "fraction"}, default "all"
        Which unloading samples a retract fit uses: all, down to the observed pull-off, or
        the top ``window_fraction`` of the unloading force range.
    window_fraction : float, default 0.5
        In (0, 1], for ``window="fraction"``.
    loss : {"none", "huber", "cauchy"}, default "none"
        Robust loss on the force residuals.
    loss_scale : float, optional
        Where the robust loss departs from least squares [N], > 0; required for huber and
        cauchy.
    starts : int, default 0
        Extra starts around the data-driven guess (0 .. 100); the lowest cost wins.
    max_iterations : int, default 200
        Trust-region iteration limit, >= 1.
    contact_point : {"fit", "threshold", "rov", "gof"}, default "fit"
        How an approach fit finds the contact point: fitted as delta0 (fit), where the force
        leaves the baseline + 5 sigma band (threshold), the ratio of variances (rov) or a
        goodness-of-fit scan of a power law (gof); docs/fitting.md defines them. With a method
        other than fit, delta0 and P0 are fixed at the found point and baseline unless freed,
        in which case the found values are their start. Needs approach samples.
    indentation_range : (float, float), optional
        (min, max) [m]: fit only the approach samples whose indentation from the contact
        point lies in the range (min < 0 keeps that much baseline). With contact_point="fit"
        the curve is fitted, the samples selected from its delta0, and fitted again.
    force_range : (float, float), optional
        (min, max), 0 <= min < max <= 1: approach samples by force, as fractions of the
        largest force above the baseline, from the first sample past the contact point that
        reaches min up to the first that exceeds max.
    baseline_window : (float, float), optional
        (min, max) [m]: the delta range of the baseline samples (baseline and noise of the
        start and of the contact-point methods); None: the quarter with the smallest delta."""


def _with_fit_parameters(function: Callable[..., Any]) -> None:
    if function.__doc__:  # None under python -OO
        function.__doc__ = function.__doc__ % _FIT_PARAMETERS_DOC.strip("\n").lstrip()


def fit(delta: npt.ArrayLike, P: npt.ArrayLike, scene: SceneLike, *,
        free: Union[str, Sequence[str]] = ("E", "w", "delta0"), segment: Optional[npt.ArrayLike] = None,
        branch: Branch = "approach", control: Control = "auto", spring_constant: Optional[float] = None,
        baseline: BaselineKind = "constant", window: Window = "all", window_fraction: float = 0.5,
        loss: Loss = "none", loss_scale: Optional[float] = None, starts: int = 0,
        max_iterations: int = 200,
        contact_point: ContactPointMethod = "fit", indentation_range: Optional[Tuple[float, float]] = None,
        force_range: Optional[Tuple[float, float]] = None,
        baseline_window: Optional[Tuple[float, float]] = None, t: Optional[npt.ArrayLike] = None) -> FitResult:
    """Fit one measured curve with the model of a scene.

    Parameters
    ----------
    delta : array_like
        Approach [m] (any offset; the fit's delta0 maps it), 1-D.
    P : array_like
        Force [N], positive when repulsive, 1-D, as long as ``delta``.
    scene : Scene, dict or path
        Indenter, medium, model and the starting values (see :func:`scene`).
    segment : array_like of int, optional
        Per sample 0 (approach), 1 (retract) or 2 (dwell); None splits the curve at its largest delta.
    t : array_like, optional
        Each sample's time [s], strictly increasing: what a relaxing medium or crack kinetics
        in the scene is fitted against (the fit is then in time).
    %s

    Returns
    -------
    FitResult

    Raises
    ------
    InputError
        Data that cannot be fitted (too few samples, no sample in contact, a parameter the
        model does not have), an unknown choice (the message names the parameter, e.g.
        ``branch``), control "cantilever" without a stiffness.
    DomainError
        An option outside its range (the message names it).
    TypeError
        An unknown keyword.

    Warns
    -----
    ModelWarning
        Each of the fit's warnings (a convergence failure is reported, not raised).
    """
    options = _options(free, branch, control, spring_constant, baseline, window, window_fraction, loss, loss_scale,
                       starts, max_iterations, contact_point, indentation_range, force_range, baseline_window)
    seg = None if segment is None else _segments(segment)
    d, p = _float64(delta), _float64(P)
    tt = None if t is None else _float64(t)
    s_ = _as_scene(scene)
    s = _core.fit(d, p, seg, tt, s_, options)
    inputs = _array_inputs(d, p, seg)
    if tt is not None:
        inputs.append(_core.record_bytes("t (float64 array)", tt))
    result = FitResult(s, options.branch, _provenance(s_, options, None, inputs))
    _warn(result.warnings, 2)
    return result


_with_fit_parameters(fit)


class Simulation(NamedTuple):
    """A synthetic curve (:func:`simulate`): float64 arrays in SI units, ``a`` and ``t`` empty
    where not made. ``fit(delta, P, scene, t=t, segment=segment)`` fits it back."""
    t: npt.NDArray[np.float64]
    delta: npt.NDArray[np.float64]
    P: npt.NDArray[np.float64]
    a: npt.NDArray[np.float64]
    segment: npt.NDArray[np.int64]
    source: str


def simulate(scene: SceneLike, *, max_indentation: float, speed: float = 0.0, retract_speed: float = 0.0,
             dwell: float = 0.0, points: int = 500, free_fraction: float = 0.5, noise: float = 0.0, seed: int = 1,
             with_radius: bool = False, branch: Branch = "all", delta0: float = 0.0, P0: float = 0.0,
             control: Literal["grips", "cantilever"] = "grips", stiffness: Optional[float] = None) -> Simulation:
    """A synthetic curve of a scene: the fit's own physics, at equilibrium or in time.

    Parameters
    ----------
    scene : Scene, dict or path
        The scene (see :func:`scene`); a relaxing medium (``medium.viscoelastic``) or crack
        kinetics (``adhesion.kinetics``) answer in time and need a ``speed``.
    max_indentation : float
        The deepest indentation beyond first contact [m], > 0.
    speed : float, default 0
        The indenter's approach speed [m/s]; > 0 samples the curve in time (``t`` from 0).
    retract_speed : float, default 0
        The retract's speed [m/s] (0: ``speed``).
    dwell : float, default 0
        A rest at the deepest point [s] (dwell samples, segment 2; needs ``speed``).
    points : int, default 500
        Samples per branch, >= 2.
    free_fraction : float, default 0.5
        Fraction of ``max_indentation`` sampled off contact, >= 0.
    noise : float, default 0
        Standard deviation of Gaussian force noise [N].
    seed : int, default 1
        The noise's seed.
    with_radius : bool, default False
        Also return the contact radius ``a`` [m].
    branch : {"approach", "retract", "all"}, default "all"
        Which samples to return (a retract in time keeps its history's times).
    delta0, P0 : float, default 0
        Contact-point offset [m] and force baseline [N] added to every sample.
    control : {"grips", "cantilever"}, default "grips"
        With crack kinetics: what drives the retract - the indenter itself, or a cantilever's
        base (``stiffness`` [N/m]).
    stiffness : float, optional
        The cantilever's stiffness [N/m] (``control="cantilever"``).

    Returns
    -------
    Simulation
        t, delta, P, a, segment and the model's name; ``layerjkr simulate`` writes the same.

    Raises
    ------
    InputError
        A relaxing medium or crack kinetics without a speed, adhesion on a relaxing medium, a
        cantilever without crack kinetics, an unknown choice (named).
    DomainError
        An option outside its range (named).
    """
    o = _core.simulation_options(
        max_indentation=_number("max_indentation", max_indentation), speed=_number("speed", speed),
        retract_speed=_number("retract_speed", retract_speed), dwell=_number("dwell", dwell),
        points=_integer("points", points), free_fraction=_number("free_fraction", free_fraction),
        noise=_number("noise", noise), seed=_integer("seed", seed), with_radius=bool(with_radius),
        branch=_text("branch", branch), delta0=_number("delta0", delta0), P0=_number("P0", P0),
        control=_text("control", control), stiffness=0.0 if stiffness is None else _number("stiffness", stiffness))
    t, d, p, a, seg, source = _core.simulate(_as_scene(scene), o)
    return Simulation(t, d, p, a, np.asarray(seg, dtype=np.int64), source)


class JointFitResult(NamedTuple):
    """Curves of one sample fitted together (:func:`fit_joint`).

    ``fit`` holds the shared parameters, then each curve's own (``"delta0[2]"``: curve 2,
    counting from 1), with one covariance; its samples are every curve's in turn, curve ``k``'s
    at ``slice(curve_begin[k], curve_begin[k + 1])``. ``alone`` has each curve fitted by
    itself, what one speed says alone."""
    fit: "FitResult"
    alone: List["FitResult"]
    curve_begin: npt.NDArray[np.int64]
    sources: List[str]


def _curve_tuple(c: Any, k: int) -> Tuple[Any, Any, Optional[List[int]], Optional[Any]]:
    """One curve of fit_joint: a Simulation, a mapping with delta, P[, segment][, t], or a tuple."""
    if isinstance(c, Simulation):
        return (_float64(c.delta), _float64(c.P), _segments(c.segment), _float64(c.t) if len(c.t) else None)
    if isinstance(c, dict):
        missing = [key for key in ("delta", "P") if key not in c]
        if missing:
            raise InputError("curves[%d] has no %s" % (k, " or ".join(missing)))
        seg, t = c.get("segment"), c.get("t")
        return (_float64(c["delta"]), _float64(c["P"]), None if seg is None else _segments(seg),
                None if t is None else _float64(t))
    if isinstance(c, (tuple, list)) and 2 <= len(c) <= 4:
        seg = c[2] if len(c) > 2 else None
        t = c[3] if len(c) > 3 else None
        return (_float64(c[0]), _float64(c[1]), None if seg is None else _segments(seg), None if t is None else _float64(t))
    raise InputError("curves[%d] is not a curve: give a Simulation, a dict with delta, P[, segment][, t], or a "
                     "tuple (delta, P[, segment[, t]])" % k)


def fit_joint(curves: Sequence[Any], scene: SceneLike, *, free: Union[str, Sequence[str]] = ("E", "delta0"),
              branch: Branch = "all", control: Control = "auto", spring_constant: Optional[float] = None,
              loss: Loss = "none", loss_scale: Optional[float] = None, max_iterations: int = 200) -> JointFitResult:
    """Fit curves of one sample at several speeds together: one law in time, shared.

    Parameters
    ----------
    curves : sequence
        At least 2 curves, each a :class:`Simulation`, a dict with ``delta``, ``P`` and optional
        ``segment`` and ``t``, or a tuple ``(delta, P[, segment[, t]])``; each with its times.
    scene : Scene, dict or path
        A relaxing medium or crack kinetics (see :func:`scene`); the starting values.
    free : sequence of str or str, default ("E", "delta0")
        As :func:`fit`; every parameter is shared but delta0 and P0, one per curve.
    branch, control, spring_constant, loss, loss_scale, max_iterations
        As :func:`fit`.

    Returns
    -------
    JointFitResult

    Raises
    ------
    InputError
        Fewer than 2 curves, an elastic scene, a curve that cannot be fitted alone (named).
    """
    options = _options(free, branch, control, spring_constant, "constant", "all", 0.5, loss, loss_scale, 0,
                       max_iterations, "fit", None, None, None)
    tuples = [_curve_tuple(c, k) for k, c in enumerate(curves)]
    s_ = _as_scene(scene)
    joint, begin, sources, alone = _core.fit_joint(tuples, s_, options)
    inputs = []
    for k, (d, p, seg, t) in enumerate(tuples):
        inputs += [_core.record_bytes("curve %d delta (float64 array)" % (k + 1), d),
                   _core.record_bytes("curve %d P (float64 array)" % (k + 1), p)]
        if t is not None:
            inputs.append(_core.record_bytes("curve %d t (float64 array)" % (k + 1), t))
    record = _provenance(s_, options, None, inputs)
    result = JointFitResult(FitResult(joint, options.branch, record), [FitResult(a, options.branch) for a in alone],
                            np.asarray(begin, dtype=np.int64), list(sources))
    _warn(result.fit.warnings, 2)
    return result


def _float64(a: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The float64 C-ordered array the library fits (and provenance hashes)."""
    return np.asarray(a, dtype=np.float64, order="C")


def _array_inputs(delta: npt.NDArray[np.float64], P: npt.NDArray[np.float64],
                  segment: Optional[List[int]]) -> List[Any]:
    inputs = [_core.record_bytes("delta (float64 array)", delta), _core.record_bytes("P (float64 array)", P)]
    if segment is not None:
        inputs.append(_core.record_bytes("segment (int64 array)", np.asarray(segment, dtype=np.int64)))
    return inputs


def _provenance(scene: Scene, options: Any, csv: Any, inputs: Sequence[Any]) -> Dict[str, Any]:
    record: Dict[str, Any] = json.loads(_core.provenance(scene, options, csv, list(inputs)))
    return record


def _with_inputs(base: Dict[str, Any], inputs: Sequence[Any]) -> Dict[str, Any]:
    """``base`` (a record without inputs) with these inputs: a dict of its own, the rest shared."""
    record = dict(base)
    record["inputs"] = [{"path": p, "size": n, "sha256": h or None, **({"error": e} if e else {})}
                        for p, n, h, e in inputs]
    return record


def _batch(items: Sequence[Any], branch: str,
           provenance: Optional[Callable[[int, Any], Dict[str, Any]]] = None) -> List[BatchResult]:
    out = []
    for k, it in enumerate(items):
        record = provenance(k, it) if provenance is not None and it.ok else None
        out.append(BatchResult(source=it.source, curve=it.curve if it.curve >= 0 else None, x=it.x, y=it.y,
                               grid_x=it.grid_x if it.grid_x >= 0 else None, grid_y=it.grid_y if it.grid_y >= 0 else None,
                               result=FitResult(it.summary, branch, record) if it.ok else None,
                               error=None if it.ok else it.error))
    return out


@contextlib.contextmanager
def _keep_finished(branch: str) -> Iterator[None]:
    # _core attaches the finished items to the exception that a signal handler raised.
    try:
        yield
    except BaseException as e:
        items = getattr(e, "batch_items", None)
        if items is not None:
            e.results = _batch(items, branch)  # type: ignore[attr-defined]
            del e.batch_items  # type: ignore[attr-defined]
        raise


def fit_batch(curves: Sequence[Tuple[npt.ArrayLike, npt.ArrayLike]], scene: SceneLike, *,
              free: Union[str, Sequence[str]] = ("E", "w", "delta0"), jobs: int = 1, branch: Branch = "approach",
              control: Control = "auto", spring_constant: Optional[float] = None,
              baseline: BaselineKind = "constant", window: Window = "all", window_fraction: float = 0.5,
              loss: Loss = "none", loss_scale: Optional[float] = None, starts: int = 0,
              max_iterations: int = 200,
              contact_point: ContactPointMethod = "fit", indentation_range: Optional[Tuple[float, float]] = None,
              force_range: Optional[Tuple[float, float]] = None,
              baseline_window: Optional[Tuple[float, float]] = None,
              report: Optional[Union[str, "os.PathLike[str]"]] = None) -> List[BatchResult]:
    """Fit many curves with the same scene and options on ``jobs`` threads.

    Parameters
    ----------
    curves : sequence of (delta, P)
        Each a pair of 1-D arrays [m], [N] (split at their largest delta).
    scene : Scene, dict or path
        See :func:`scene`.
    jobs : int, default 1
        Worker threads, >= 1 (the GIL is released).
    %s
    report : path, optional
        Also write the interactive report (as ``fit-map --report``; see :func:`fit_files`)
        to ``report/index.html``; the curves, having no map position, are laid out by index.

    Returns
    -------
    list of BatchResult
        One per curve, in order: its FitResult (without the per-sample arrays, or with
        ``report``, with the thinned ones the report shows) or the error message. A curve that
        cannot be fitted never stops the batch. The fits' warnings are in each result, not
        emitted.

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C (checked every 0.1 s): no further curve starts, the running fits finish,
        and the exception's ``results`` holds the finished curves (a prefix of the input, as
        BatchResults). The same for any exception a signal handler raises.
    InputError
        An invalid option (named), ``jobs`` < 1, an array not 1-D.
    DomainError
        An option outside its range.
    TypeError
        An unknown keyword.
    """
    options = _options(free, branch, control, spring_constant, baseline, window, window_fraction, loss, loss_scale,
                       starts, max_iterations, contact_point, indentation_range, force_range, baseline_window)
    pairs = [(_float64(d), _float64(p)) for d, p in curves]
    s = _as_scene(scene)
    directory = _report_dir(report)
    with _keep_finished(options.branch):
        items = _core.fit_batch(pairs, s, options, _integer("jobs", jobs),
                                _core.DEFAULT_DISPLAY_POINTS if directory else 0)
    if directory:
        _write_report(items, options, directory, "%d curves (fit_batch)" % len(items))
    base = _provenance(s, options, None, [])
    return _batch(items, options.branch, lambda k, it: _with_inputs(base, _array_inputs(*pairs[k], None)))


_with_fit_parameters(fit_batch)


def fit_files(paths: Union[str, "os.PathLike[str]", Sequence[Union[str, "os.PathLike[str]"]]], scene: SceneLike, *,
              free: Union[str, Sequence[str]] = ("E", "w", "delta0"), jobs: int = 1, branch: Branch = "approach",
              control: Control = "auto", spring_constant: Optional[float] = None,
              baseline: BaselineKind = "constant", window: Window = "all", window_fraction: float = 0.5,
              loss: Loss = "none", loss_scale: Optional[float] = None, starts: int = 0, max_iterations: int = 200,
              units: str = "m,N", z_sign: float = 1.0, deflection_sign: float = 1.0,
              curve: Optional[int] = None, curves: Optional[CurveRangeLike] = None,
              contact_point: ContactPointMethod = "fit", indentation_range: Optional[Tuple[float, float]] = None,
              force_range: Optional[Tuple[float, float]] = None,
              baseline_window: Optional[Tuple[float, float]] = None,
              report: Optional[Union[str, "os.PathLike[str]"]] = None) -> List[BatchResult]:
    """Fit CSV and instrument files on ``jobs`` threads, as ``layerjkr fit-map``.

    Parameters
    ----------
    paths : path or sequence of paths
        CSV files and instrument files (.jpk-force, .jpk-force-map, .jpk-qi-data, .ibw); every
        curve of a map is its own item.
    scene : Scene, dict or path
        See :func:`scene`.
    jobs : int, default 1
        Worker threads, >= 1 (the GIL is released).
    %s
    units : str, default "m,N"
        Units of the CSV files, "LENGTH,FORCE", e.g. "nm,nN".
    z_sign : float, default 1.0
        Raw z,deflection CSV: +1 if z grows towards the sample, -1 if it decreases.
    deflection_sign : float, default 1.0
        Raw z,deflection CSV: +1 if a deflection > 0 means repulsion, else -1.
    curve : int, optional
        Which curve of a CSV export holding several.
    curves : slice or (int, int), optional
        Fit only the curves at these positions of each instrument file (0-based, file order,
        as ``fit-map --curves A:B``): ``slice(a, b)`` or ``(a, b)`` for positions a .. b - 1,
        ``slice(a, None)`` for a to the end. Only those curves are read. A range that selects
        no curve of a file is that file's failed item. CSV files are unaffected. None: every
        curve.
    report : path, optional
        A directory for the interactive report, as ``layerjkr fit-map --report``: one
        self-contained page, ``report/index.html``, that works from file:// without network
        (a heat map per fitted field with colour bar and histogram, bad pixels marked, a
        status filter, each curve with its fit; docs/report.md). The directory is created; an
        existing one must be empty or hold an earlier report (only its index.html), checked
        before any fitting. Not written if the batch is interrupted.

    ``spring_constant`` is also the one the CSV reader uses for z,deflection data and that
    replaces an instrument file's own.

    Returns
    -------
    list of BatchResult
        One per curve, in file order, with its map position and pixel: its FitResult
        (without the per-sample arrays, or with ``report``, with the thinned ones the report
        shows) or the error message. A file that cannot be read is
        one failed item (so is a path that is not a regular file: a directory, a FIFO, a
        dangling or looping link, never opened). The fits' warnings are in each result, not
        emitted.

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C (checked every 0.1 s): no further curve starts, the running fits finish,
        and the exception's ``results`` holds the finished curves (a prefix of the input, as
        BatchResults). The same for any exception a signal handler raises.
    InputError
        An invalid option (named), unknown units, ``jobs`` < 1; a ``curves`` range with a
        step other than 1, a negative bound or its begin after its end; a ``report`` that is a
        file, cannot be created or written, or is a directory holding other files.
    DomainError
        An option outside its range.
    TypeError
        An unknown keyword; a ``curves`` that is not a slice or a pair of integers.
    """
    options = _options(free, branch, control, spring_constant, baseline, window, window_fraction, loss, loss_scale,
                       starts, max_iterations, contact_point, indentation_range, force_range, baseline_window)
    selection = None
    if curves is not None:
        begin, end = _curve_range(curves)
        selection = (begin, _NO_END if end is None else end)
    csv = _core.csv_options(units=_text("units", units),
                            spring_constant=None if spring_constant is None else _number("spring_constant", spring_constant),
                            z_sign=_number("z_sign", z_sign), deflection_sign=_number("deflection_sign", deflection_sign),
                            curve=None if curve is None else _integer("curve", curve))
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    # As bytes, the file system's own names: a name that is not UTF-8 (os.listdir gives it with
    # surrogates) reaches the file; each result's source gives it back as os.fsdecode would.
    names = [os.fsencode(p) for p in paths]
    s = _as_scene(scene)
    directory = _report_dir(report)
    # Each file hashed once, before it is read (a FIFO or a directory is recorded, not opened).
    hashed = {name: _core.record_file(name) for name in names}
    with _keep_finished(options.branch):
        items = _core.fit_files(names, s, options, csv, _integer("jobs", jobs), selection,
                                _core.DEFAULT_DISPLAY_POINTS if directory else 0)
    if directory:
        _write_report(items, options, directory, "%d input file(s) (fit_files)" % len(names))
    base = _provenance(s, options, csv, [])
    return _batch(items, options.branch,
                  lambda k, it: _with_inputs(base, [hashed.get(os.fsencode(it.source)) or _core.record_file(os.fsencode(it.source))]))


def _report_dir(report: Optional[Union[str, "os.PathLike[str]"]]) -> Optional[str]:
    """The report's directory, created and checked before any fitting (None: no report)."""
    if report is None:
        return None
    directory = os.fspath(report)
    _core.prepare_report_dir(directory, "report")
    return directory


def _write_report(items: Sequence[Any], options: Any, directory: str, subtitle: str) -> None:
    """Writes the report's page atomically: a private temporary file renamed over index.html,
    which keeps the mode and owner of a page it replaces (as the CLI's outputs do)."""
    html = _core.map_report_html(items, options, "layerjkr force-map report", subtitle)
    target = os.path.join(directory, "index.html")
    fd, tmp = tempfile.mkstemp(prefix=".index.html.", dir=directory)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(html)
            f.flush()
            os.fsync(f.fileno())
        try:
            old = os.stat(target)
            if (old.st_uid, old.st_gid) != (os.getuid(), os.getgid()):
                os.chown(tmp, old.st_uid, old.st_gid)
            os.chmod(tmp, old.st_mode & 0o7777)
        except FileNotFoundError:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


_with_fit_parameters(fit_files)


# CurveRange's "to the last curve" as the binding takes it: any end past the last curve stops
# there, and sys.maxsize fits a size_t on every platform.
_NO_END = sys.maxsize


def _curve_range(curves: Any) -> Tuple[int, Optional[int]]:
    """``curves`` as (begin, end or None): positions in file order, as the CLI's --curves A:B.

    Negative bounds are refused rather than counted from the end: that would need the file's
    length before reading, and a range is meant to name the same curves in every file."""
    if isinstance(curves, slice):
        if curves.step is not None and curves.step != 1:
            raise InputError("curves = %r: a step of %r; a range of curves is contiguous (step 1)" % (curves, curves.step))
        start, stop = curves.start, curves.stop
    elif isinstance(curves, tuple) and len(curves) == 2:
        start, stop = curves
        if start is None or stop is None:
            raise TypeError("curves = %r: a pair needs two integers (begin, end); use a slice for an open end" % (curves,))
    else:
        raise TypeError("curves must be a slice or a pair of integers (begin, end), got %s %r"
                        % (type(curves).__name__, curves))
    begin = 0 if start is None else _integer("curves begin", start)
    end = None if stop is None else _integer("curves end", stop)
    if begin < 0 or (end is not None and end < 0):
        raise InputError("curves = %r: positions are >= 0 (counted from the file's first curve, not its end)" % (curves,))
    if end is not None and begin > end:
        raise InputError("curves = %r: begin %d is after end %d" % (curves, begin, end))
    return begin, end


def read_instrument(path: Union[str, "os.PathLike[str]"], *,
                    curves: Optional[CurveRangeLike] = None) -> List[Dict[str, Any]]:
    """The curves of an instrument file, or of a range of its curves.

    Parameters
    ----------
    path : str or os.PathLike
        A JPK (.jpk-force, .jpk-force-map, .jpk-qi-data), Igor (.ibw) or Bruker NanoScope
        (.spm, .000 - .999) file.
    curves : slice or (int, int), optional
        Read only the curves at these positions (0-based, file order): ``slice(a, b)`` or
        ``(a, b)`` for a .. b - 1, ``slice(a, None)`` for a to the end; as list slicing, an
        end past the last curve stops there. Only the range is read from the file. None:
        every curve.

    Returns
    -------
    list of dict
        Per curve: delta (= -tip position) [m] and P [N] as float64 arrays, segment (0
        approach, 1 retract), index (the curve's number in the file), spring_constant [N/m],
        sensitivity, x, y [m], grid_x, grid_y. ``read_instrument(p, curves=(a, b))`` equals
        ``read_instrument(p)[a:b]``.

    Raises
    ------
    InputError
        A file that cannot be read or parsed (the message names it); a ``curves`` range with
        a step other than 1, a negative bound or its begin after its end (InputError is a
        ValueError).
    TypeError
        A ``curves`` that is not a slice or a pair of integers.

    See Also
    --------
    open_instrument : random access to any curve without reading the others.
    """
    begin, end = (0, None) if curves is None else _curve_range(curves)
    return _core.read_instrument(os.fspath(path), begin, end)


class Instrument(Sequence[Dict[str, Any]]):
    """An instrument file opened for random access: ``open_instrument(path)``.

    Opening reads the header and the index of the curves, never the samples; ``f[i]`` then
    reads curve i alone and ``f[a:b]`` the curves a .. b - 1 (any step), each as the dict
    :func:`read_instrument` returns, with the GIL released. Reads from several threads at
    once are safe. Use it as a context manager, or :meth:`close` it, to release the file.

    Attributes
    ----------
    header : dict
        The file's metadata: path, format ("jpk-force", "jpk-force-map", "jpk-qi-data",
        "ibw", "nanoscope"), instrument, software, grid_shape (x, y; (0, 0) if not a map),
        grid_size (x, y) [m], grid_center (x, y) [m].
    """

    def __init__(self, path: Union[str, "os.PathLike[str]"]) -> None:
        self._reader = _core.InstrumentReader(os.fspath(path))
        self._header: Dict[str, Any] = self._reader.header
        self._size: int = len(self._reader)

    @property
    def header(self) -> Dict[str, Any]:
        return dict(self._header)  # a copy: the caller may change it

    @property
    def path(self) -> str:
        return str(self._header["path"])

    @property
    def closed(self) -> bool:
        return bool(self._reader.closed)

    def __len__(self) -> int:
        return self._size

    def _position(self, i: Any) -> int:
        k = _integer("curve position", i)
        if k < 0:
            k += self._size  # a sequence's negative index: the file's length is known here
        if not 0 <= k < self._size:
            raise IndexError("curve position %d is outside %s's %d curves" % (i, self.path, self._size))
        return k

    @overload
    def __getitem__(self, key: int) -> Dict[str, Any]: ...

    @overload
    def __getitem__(self, key: slice) -> List[Dict[str, Any]]: ...

    def __getitem__(self, key: Union[int, slice]) -> Union[Dict[str, Any], List[Dict[str, Any]]]:
        if isinstance(key, slice):
            return list(self._reader.curves(list(range(*key.indices(self._size)))))
        return dict(self._reader.curves([self._position(key)])[0])

    def curve_number(self, i: int) -> int:
        """The number curve ``i`` carries in the file (JPK's index/N, else its position),
        without reading the curve."""
        return int(self._reader.curve_number(self._position(i)))

    def close(self) -> None:
        """Releases the file; reads after it raise ValueError (the header stays readable)."""
        self._reader.close()

    def __enter__(self) -> "Instrument":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __reduce__(self) -> Any:
        # Pickled as its path (Dask ships it to a worker, which opens the file itself).
        return (open_instrument, (self.path,))

    def __repr__(self) -> str:
        h = self._header
        grid = " on a %dx%d grid" % tuple(h["grid_shape"]) if h["grid_shape"][0] > 0 else ""
        return "<layerjkr.Instrument %r: %s, %d curves%s%s>" % (self.path, h["format"], self._size, grid,
                                                               " (closed)" if self.closed else "")


def open_instrument(path: Union[str, "os.PathLike[str]"]) -> Instrument:
    """Opens an instrument file for random access to its curves.

    Parameters
    ----------
    path : str or os.PathLike
        A JPK (.jpk-force, .jpk-force-map, .jpk-qi-data), Igor (.ibw) or Bruker NanoScope
        (.spm, .000 - .999) file.

    Returns
    -------
    Instrument
        ``len(f)`` curves; ``f[i]``, ``f[a:b]`` read them (the dicts of
        :func:`read_instrument`), ``f.header`` the metadata, ``f.curve_number(i)`` the number
        curve i carries. Only the header and the index are read here (a 65 536-curve QI map
        opens in about 0.6 s), so splitting a map into ranges starts cheaply:
        ``n = len(layerjkr.open_instrument(path))``.

    Raises
    ------
    InputError
        A missing file, one of no known format, or a header that cannot be read (named).

    Examples
    --------
    >>> with layerjkr.open_instrument("map.jpk-qi-data") as f:  # doctest: +SKIP
    ...     first, last = f[0], f[-1]
    ...     some = f[100:200]          # == layerjkr.read_instrument(path, curves=(100, 200))
    """
    return Instrument(path)
