"""Profile (likelihood) intervals of a fitted parameter (FitResult.profile): where the fit's
chi-square, with the parameter held and every other free parameter refitted, has risen by
`sigmas`^2 times the reduced chi-square - the interval lmfit's conf_interval and iminuit's
minos give, which follows a curved or bounded objective where the symmetric error bar cannot."""
from __future__ import annotations

import math
import warnings
from typing import Any, Callable, NamedTuple

from ._core import Error, InputError


class ProfileInterval(NamedTuple):
    """A parameter's profile interval (:meth:`FitResult.profile`)."""
    name: str
    value: float
    """The fitted value."""
    lower: float
    upper: float
    sigmas: float
    """Half-width in standard errors the interval stands for (1: 68.3 %, 2: 95.4 %)."""
    standard_error: float
    """The symmetric error bar, for comparison."""
    lower_at_domain_edge: bool
    """The lower end is where the parameter's domain ends (e.g. w = 0), not a rise of chi-square."""
    upper_at_domain_edge: bool
    fits: int
    """The refits it took."""


# The ends are found to this fraction of the standard error (bisection).
_TOLERANCE = 1e-3
_MAX_DOUBLINGS = 30


def profile(result: Any, name: str, sigmas: float = 1.0) -> ProfileInterval:
    """See :meth:`FitResult.profile`."""
    again: Callable[..., Any] = getattr(result, "_again", None)
    if again is None:
        raise InputError("FitResult.profile: this result cannot be refitted (a batch's, a joint fit's or an "
                         "unpickled one): fit the curve with layerjkr.fit")
    if name not in result.parameters:
        raise InputError("FitResult.profile: %r is not a free parameter (free: %s)" % (name, ", ".join(result.parameters)))
    if name in ("delta0", "P0"):
        raise InputError("FitResult.profile: %s belongs to the data, not the scene, and cannot be held" % name)
    if not (isinstance(sigmas, (int, float)) and 0.0 < sigmas <= 10.0):
        raise InputError("FitResult.profile: sigmas = %r is invalid; valid range: (0, 10]" % (sigmas,))
    if not result.converged or result.ndata <= result.nvarys:
        raise InputError("FitResult.profile: the fit did not converge or has no degrees of freedom")
    value, se = float(result.values[name]), float(result.errors[name])
    step = se if math.isfinite(se) and se > 0.0 else 0.1 * abs(value) if value != 0.0 else 1e-3
    chi0, s2 = result.chisqr, result.chisqr / (result.ndata - result.nvarys)
    others = [q for q in result.parameters if q != name]
    start = {q: float(result.values[q]) for q in others if q not in ("delta0", "P0")}
    count = [0]

    def deviance(v: float) -> float:
        """The rise of chi-square in reduced-chi-square units with `name` held at v; inf outside
        the parameter's domain (the scene refuses v) or where the refit fails."""
        count[0] += 1
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = again(free=others, fixed={name: v}, start=start or None)
        except Error:
            return math.inf
        return (r.chisqr - chi0) / s2 if r.converged else math.inf

    target = sigmas * sigmas
    ends, edges = [], []
    for side in (-1.0, 1.0):
        inner, offset = value, step * sigmas
        outer = value + side * offset
        d = deviance(outer)
        for _ in range(_MAX_DOUBLINGS):
            if d > target:
                break
            inner, offset = outer, 2.0 * offset
            outer = value + side * offset
            d = deviance(outer)
        edge = math.isinf(d)
        while abs(outer - inner) > _TOLERANCE * step:
            mid = 0.5 * (inner + outer)
            dm = deviance(mid)
            if dm > target:
                outer, edge = mid, math.isinf(dm)
            else:
                inner = mid
        ends.append(inner if edge else 0.5 * (inner + outer))
        edges.append(edge)
    return ProfileInterval(name, value, ends[0], ends[1], float(sigmas), se, edges[0], edges[1], count[0])
