"""The options every fit function shares (free parameters, branch, control, ranges), their
documentation and the provenance record of array inputs."""
from __future__ import annotations

import difflib
import json
import math
import re
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import InputError, Scene
from ._common import _integer, _number, _positive, _text


# The names a fit frees (FitParameter's string registry, with its aliases T, w0 and V).
_PARAMETER_NAMES = ("K", "G", "T", "w", "w0", "delta0", "P0", "E", "R", "sigma0", "E_inf", "tau", "E_2", "tau_2",
                    "beta", "v_star", "V", "n", "drag")


def _parameter_name(name: str) -> str:
    """``name`` if it is a parameter, else InputError with the closest one ("W": did you mean "w")."""
    if name in _PARAMETER_NAMES:
        return name
    same_case = [p for p in _PARAMETER_NAMES if p.lower() == name.lower()]
    close = same_case or difflib.get_close_matches(name, _PARAMETER_NAMES, n=1, cutoff=0.5)
    hint = '; did you mean "%s"?' % close[0] if close else ""
    raise InputError('free = "%s" is unknown%s (known: %s)' % (name, hint, ", ".join(_PARAMETER_NAMES)))


def _free(free: Union[str, Sequence[str]]) -> List[str]:
    """The free parameters: a sequence of names, or one string separated by commas and/or spaces."""
    if isinstance(free, str):
        free = [f for f in re.split(r"[,\s]+", free) if f]
    if not hasattr(free, "__iter__"):
        raise TypeError("free must be a string or a sequence of names, got %s %r" % (type(free).__name__, free))
    return [_parameter_name(_text("free", f).strip()) for f in free]


def _options(free: Union[str, Sequence[str]], branch: str, control: str, spring_constant: Optional[float],
             baseline: str, window: str, window_fraction: float, loss: str, loss_scale: Optional[float], starts: int,
             max_iterations: int, contact_point: str = "fit",
             indentation_range: Optional[Tuple[float, float]] = None, force_range: Optional[Tuple[float, float]] = None,
             baseline_window: Optional[Tuple[float, float]] = None, bounds: Any = None,
             displacement_noise: Union[None, float, str] = None, force_noise: Optional[float] = None) -> Any:
    if isinstance(displacement_noise, str) and displacement_noise != "auto":
        raise InputError("displacement_noise = %r is invalid; give the noise [m], \"auto\" to estimate it, or None"
                         % (displacement_noise,))
    given = None if displacement_noise is None or displacement_noise == "auto" else \
        _positive("displacement_noise", displacement_noise, "m")
    return _core.fit_options(free=_free(free), branch=_text("branch", branch), control=_text("control", control),
                             spring_constant=None if spring_constant is None else _positive("spring_constant", spring_constant, "N/m"),
                             baseline=_text("baseline", baseline), window=_text("window", window),
                             window_fraction=_number("window_fraction", window_fraction), loss=_text("loss", loss),
                             loss_scale=None if loss_scale is None else _number("loss_scale", loss_scale),
                             starts=_integer("starts", starts), max_iterations=_integer("max_iterations", max_iterations),
                             contact_point=_text("contact_point", contact_point),
                             indentation_range=_range("indentation_range", indentation_range),
                             force_range=_range("force_range", force_range),
                             baseline_window=_range("baseline_window", baseline_window), bounds=_bounds(bounds),
                             errors_in_displacement=displacement_noise is not None, displacement_noise=given,
                             force_noise=None if force_noise is None else _positive("force_noise", force_noise, "N"))


def _bounds(bounds: Any) -> List[Tuple[str, float, float]]:
    """fit(bounds={"E": (1e3, 1e5), "w": (0, None)}) as (name, lower, upper); None is no bound."""
    if bounds is None:
        return []
    if not isinstance(bounds, dict):
        raise InputError("bounds = %r is invalid; give a mapping of parameter names to (lower, upper), e.g. "
                         "{\"E\": (1e3, 1e5), \"w\": (0, None)}" % (bounds,))
    out = []
    for name, pair in bounds.items():
        if not isinstance(name, str) or not isinstance(pair, (tuple, list)) or len(pair) != 2:
            raise InputError("bounds[%r] = %r is invalid; give (lower, upper), None for no bound" % (name, pair))
        lower = -math.inf if pair[0] is None else _number("bounds[%r] lower" % name, pair[0])
        upper = math.inf if pair[1] is None else _number("bounds[%r] upper" % name, pair[1])
        out.append((name, lower, upper))
    return out


def _range(name: str, value: Optional[Tuple[float, float]]) -> Optional[Tuple[float, float]]:
    if value is None:
        return None
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise InputError("%s = %r is invalid; give (min, max) or None" % (name, value))
    return (_number(name, value[0]), _number(name, value[1]))


_FIT_PARAMETERS_DOC = """
    free : sequence of str or str, default ("E", "w", "delta0", "P0")
        Parameters to identify: K, G (or T), w, delta0, P0, E, R, sigma0, and in time E_inf, tau
        (a standard linear solid), beta (a power law; with E_inf a power_law_plateau), beta and tau
        (a fractional law; with E_inf a fractional_sls), E_2 and tau_2 (with E_inf and tau: a
        two-term Maxwell law, maxwell2), v_star, n
        (crack kinetics), drag (the lever's drag [N s/m] in liquid, with a relaxing medium); a
        comma-separated string is accepted too. The others come from the
        scene (delta0 = P0 = 0 unless freed). The baseline P0 is free by default, as instrument curves need: with it
        fixed, a fit whose answer moves by more than 3 error bars when P0 is freed warns so.
    branch : {"approach", "retract", "all", "dwell", "approach_dwell"}, default "approach"
        Which part of the curve to fit; "dwell" and "approach_dwell" are fits in time of a curve
        with a dwell (its samples alone, or with the approach; what precedes enters as history).
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


def _array_inputs(delta: npt.NDArray[np.float64], P: npt.NDArray[np.float64],
                  segment: Optional[npt.NDArray[np.int64]]) -> List[Any]:
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
