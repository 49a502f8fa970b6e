"""Fitting one curve (fit) and several curves of one sample jointly (fit_joint); simulating a
curve is _simulate's."""
from __future__ import annotations

import html
import math

from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import InputError, NumericalError, Scene
from ._common import BaselineKind, Branch, ContactPointMethod, Control, Loss, SceneLike, Window, _float64, _number, _segments, _sequence, _text, _warn
from ._html import number, table
from ._scene import _as_scene
from ._fit_result import FitResult
from ._fit_options import _array_inputs, _options, _provenance, _with_fit_parameters
from ._simulate import Simulation


def fit(delta: npt.ArrayLike, P: npt.ArrayLike, scene: SceneLike, *,
        free: Union[str, Sequence[str]] = ("E", "w", "delta0", "P0"), segment: Optional[npt.ArrayLike] = None,
        branch: Branch = "approach", control: Control = "auto", spring_constant: Optional[float] = None,
        baseline: BaselineKind = "constant", window: Window = "all", window_fraction: float = 0.5,
        loss: Loss = "none", loss_scale: Optional[float] = None, starts: int = 0,
        max_iterations: int = 200,
        contact_point: ContactPointMethod = "fit", indentation_range: Optional[Tuple[float, float]] = None,
        force_range: Optional[Tuple[float, float]] = None,
        baseline_window: Optional[Tuple[float, float]] = None, t: Optional[npt.ArrayLike] = None,
        units: str = "m,N", start: Optional[Mapping[str, float]] = None,
        fixed: Optional[Mapping[str, float]] = None,
        bounds: Optional[Mapping[str, Tuple[Optional[float], Optional[float]]]] = None,
        displacement_noise: Union[None, float, str] = None, force_noise: Optional[float] = None) -> FitResult:
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
    units : str, default "m,N"
        Units of ``delta`` and ``P``, "LENGTH,FORCE" as for :func:`fit_files` (LENGTH in m, mm,
        um, nm, pm; FORCE in N, mN, uN, nN, pN), e.g. "nm,nN"; the result is in SI units.
    start : mapping of str to float, optional
        Starting values of free parameters, e.g. ``{"E": 5e3, "w": 1e-4}`` (SI units): they
        replace the scene's values, from which the data-driven start is sought. Every key must be
        in ``free``.
    bounds : mapping of str to (float or None, float or None), optional
        Ranges of free parameters in SI units, e.g. ``{"E": (1e3, 1e5), "w": (0, None)}`` (None:
        no bound on that side). Every solve keeps them; a parameter that ends at an end has no
        error bar (``at_bound``) and a ModelWarning says the range, not the data, decides it.
        Elastic fits only.
    displacement_noise : float or "auto", optional
        Errors in both variables, for (delta, P) data whose displacement has noise of its own (a
        JKR rig's sensor, not an AFM's delta = z - P/k): each sample's residual is its distance to
        the curve, force and displacement each in its own noise (orthogonal distance regression, as
        scipy.odr). The noise [m], or "auto" to estimate it from the data; None: delta is exact.
    force_noise : float, optional
        With ``displacement_noise``: the force's noise [N]; None estimates it from the data.
    fixed : mapping of str to float, optional
        Values of parameters held fixed, e.g. ``{"w": 0.0}`` or ``{"R": 2e-5}``: they replace the
        scene's. No key may be in ``free``; delta0 and P0 belong to the data (shift ``delta`` or
        ``P`` instead).

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
    call = dict(locals())  # the arguments as given: FitResult.profile refits with some changed
    options = _options(free, branch, control, spring_constant, baseline, window, window_fraction, loss, loss_scale,
                       starts, max_iterations, contact_point, indentation_range, force_range, baseline_window, bounds,
                       displacement_noise, force_noise)
    seg = None if segment is None else _segments(segment)
    length, force = _core.unit_scales(_text("units", units))
    d, p = _float64(delta, "delta") * length, _float64(P, "P") * force
    tt = None if t is None else _float64(t, "t")
    s_ = _with_values(_as_scene(scene), options.free, start, fixed)
    try:
        s = _core.fit(d, p, seg, tt, s_, options)
    except (InputError, NumericalError) as e:
        hint = _unit_hint(d, p) if units.replace(" ", "") == "m,N" else ""
        if not hint:
            raise
        raise type(e)(str(e) + hint) from None
    t_fitted = None if tt is None else tt.copy()  # _float64 may return the caller's own array

    def record() -> Dict[str, Any]:  # made when the result's provenance is first asked for
        inputs = _array_inputs(d, p, seg)
        if t_fitted is not None:
            inputs.append(_core.record_bytes("t (float64 array)", t_fitted))
        return _provenance(s_, options, None, inputs)

    result = FitResult(s, options.branch, record)
    def again(**changes: Any) -> FitResult:  # the same call with some arguments changed (profile)
        merged = {**call, **changes, "fixed": {**(call["fixed"] or {}), **changes.get("fixed", {})}}
        if call["bounds"] and "free" in changes:  # a held parameter's range goes with it
            merged["bounds"] = {k: v for k, v in call["bounds"].items() if k in changes["free"]}
        return fit(**merged)

    result._again = again
    _warn(result.warnings, 2)
    return result


_with_fit_parameters(fit)


def _with_values(scene: Scene, free: Sequence[str], start: Optional[Mapping[str, float]],
                 fixed: Optional[Mapping[str, float]]) -> Scene:
    """The scene with fit(start=, fixed=) in place of its own values (the C++ fitted_scene)."""
    values: List[Tuple[str, float]] = []
    for arg, given in (("start", start), ("fixed", fixed)):
        if given is None:
            continue
        if not isinstance(given, Mapping):
            raise InputError("%s = %r is invalid; give a mapping of parameter names to values, e.g. {\"E\": 5e3}"
                             % (arg, given))
        for name, value in given.items():
            if not isinstance(name, str):
                raise InputError("%s: key %r is not a parameter name" % (arg, name))
            if (name in free) != (arg == "start"):
                raise InputError("%s[%r]: %s" % (arg, name, "not in free = %s: only a free parameter has a start" % list(free)
                                                 if arg == "start" else "is free: fix it by leaving it out of free"))
            if name in ("delta0", "P0"):
                raise InputError("%s[%r]: delta0 and P0 belong to the data, not the scene: shift delta or P instead"
                                 % (arg, name))
            v = _number("%s[%r]" % (arg, name), value)
            if not math.isfinite(v):
                raise InputError("%s[%r] = %r is invalid; give a finite value in SI units" % (arg, name, value))
            values.append((name, v))
    if not values:
        return scene
    if not scene.json:
        raise InputError("start= and fixed= edit the scene's JSON, and this scene was built in code without one: "
                         "set the values in the scene itself")
    try:
        return _core.fitted_scene(scene.json, values)
    except InputError as e:
        raise InputError("fit(start=, fixed=): %s" % e) from None


def _unit_hint(delta: npt.NDArray[np.float64], P: npt.NDArray[np.float64]) -> str:
    """A hint for a fit that failed on data whose size says they are not in metres and newtons:
    AFM indentations of 1 mm or forces of 1 N are nanometres and nanonewtons read as SI."""
    span_d = float(np.nanmax(np.abs(delta))) if delta.size else 0.0
    span_P = float(np.nanmax(np.abs(P))) if P.size else 0.0
    if span_d <= 1e-3 and span_P <= 1.0:
        return ""
    return (" [the data reach |delta| = %.3g m and |P| = %.3g N: if they are in nm and nN (or other units), "
            "pass units=\"nm,nN\"]" % (span_d, span_P))


class JointFitResult(NamedTuple):
    """Curves of one sample fitted together (:func:`fit_joint`).

    ``fit`` holds the shared parameters, then each curve's own (``"delta0[1]"``: ``curves[1]``'s,
    counting from 0 as ``alone`` and ``curve_begin`` do), with one covariance; its samples are every curve's in turn, curve ``k``'s
    at ``slice(curve_begin[k], curve_begin[k + 1])``. ``alone`` has each curve fitted by
    itself, what one speed says alone."""
    fit: "FitResult"
    alone: List["FitResult"]
    curve_begin: npt.NDArray[np.int64]
    sources: List[str]

    def _repr_html_(self) -> str:
        # The joint fit's table, then each shared parameter as each curve alone gives it.
        shared = [p for p in self.fit.parameters if "[" not in p]
        rows = [(html.escape(source),) + tuple(
            "%s +- %s" % (number(a.values[p]), number(a.errors[p], 2)) if p in a.parameters else "-" for p in shared)
            for source, a in zip(self.sources, self.alone)]
        return self.fit._repr_html_() + table("each curve fitted alone", ("curve",) + tuple(shared), rows)


def _curve_tuple(c: Any, k: int) -> Tuple[Any, Any, Optional[List[int]], Optional[Any]]:
    """One curve of fit_joint: a Simulation, a mapping with delta, P[, segment][, t], or a tuple."""
    if isinstance(c, Simulation):
        return (_float64(c.delta), _float64(c.P), _segments(c.segment), _float64(c.t) if len(c.t) else None)
    if isinstance(c, dict):
        missing = [key for key in ("delta", "P") if key not in c]
        if missing:
            raise InputError("curves[%d] has no %s" % (k, " or ".join(missing)))
        seg, t = c.get("segment"), c.get("t")
        return (_float64(c["delta"], "curves[%d] delta" % k), _float64(c["P"], "curves[%d] P" % k),
                None if seg is None else _segments(seg), None if t is None else _float64(t, "curves[%d] t" % k))
    if isinstance(c, (tuple, list)) and 2 <= len(c) <= 4:
        seg = c[2] if len(c) > 2 else None
        t = c[3] if len(c) > 3 else None
        return (_float64(c[0], "curves[%d] delta" % k), _float64(c[1], "curves[%d] P" % k),
                None if seg is None else _segments(seg), None if t is None else _float64(t, "curves[%d] t" % k))
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
    tuples = [_curve_tuple(c, k) for k, c in enumerate(_sequence("curves", curves))]
    s_ = _as_scene(scene)
    joint, begin, sources, alone = _core.fit_joint(tuples, s_, options)
    inputs = []
    for k, (d, p, seg, t) in enumerate(tuples):
        inputs += [_core.record_bytes("curves[%d] delta (float64 array)" % k, d),
                   _core.record_bytes("curves[%d] P (float64 array)" % k, p)]
        if t is not None:
            inputs.append(_core.record_bytes("curves[%d] t (float64 array)" % k, t))
    record = _provenance(s_, options, None, inputs)
    result = JointFitResult(FitResult(joint, options.branch, record), [FitResult(a, options.branch) for a in alone],
                            np.asarray(begin, dtype=np.int64), list(sources))
    _warn(result.fit.warnings, 2)
    return result
