"""What a FitResult becomes: the fitted scene, the fitted force at any indentation, a plot of
data, fit and residuals, and an HTML table for notebooks. FitResult's methods call these."""
from __future__ import annotations

import html
import json
import math
from typing import Any, Optional

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import InputError, Scene
from ._common import _float64, _text
from ._html import number, table
from ._simulate import simulate


def fitted_scene(result: Any) -> Scene:
    """The fit's scene with its fitted values in place (C++ fitted_scene)."""
    record = result.provenance.get("scene") if isinstance(result.provenance, dict) else None
    spec = record.get("json") if isinstance(record, dict) else None
    if spec is None:
        raise InputError("FitResult.scene: the fit's scene was built in code (no JSON in its provenance); "
                         "put the fitted values into that scene yourself")
    values = [(name, float(value)) for name, value in zip(result.parameters, result.values.view(np.ndarray))]
    return _core.fitted_scene(json.dumps(spec), values)


def _offsets(result: Any) -> "tuple[float, float]":
    """delta0 and P0 as the fit used them: fitted, found by a contact-point method, or 0."""
    point = result.contact_point
    delta0 = point.get("value", 0.0)
    delta0 = delta0 if isinstance(delta0, float) and math.isfinite(delta0) else 0.0
    if "delta0" in result.parameters:
        delta0 = float(result.values["delta0"])
    baseline = point.get("baseline", math.nan)
    P0 = baseline if isinstance(baseline, float) and math.isfinite(baseline) else 0.0
    if "P0" in result.parameters:
        P0 = float(result.values["P0"])
    return delta0, P0


def evaluate(result: Any, delta: npt.ArrayLike, branch: Optional[str]) -> npt.NDArray[np.float64]:
    """The fitted force [N] at approaches ``delta`` [m] on one branch (FitResult.eval)."""
    if result.t.size:
        raise InputError("FitResult.eval: a fit in time has a force that depends on the history, not on delta "
                         "alone; simulate(result.scene, speed=...) gives the curve at a speed")
    chosen = _text("branch", branch if branch is not None else result._branch)
    if chosen not in ("approach", "retract"):
        raise InputError("FitResult.eval: branch = %r is invalid; give \"approach\" or \"retract\" (the fit used "
                         "both: say which)" % chosen)
    d = _float64(delta)
    delta0, P0 = _offsets(result)
    out = np.full(d.shape, np.nan)  # NaN in, NaN out
    finite = np.isfinite(d)
    if not finite.any():
        return out
    # Each point's force comes from a curve simulated to the decade of its own |delta - delta0|
    # (4 000 samples to 10^(g+1) m for 10^g <= |delta - delta0| < 10^(g+1)): what one point gets
    # never depends on the others asked for with it (one point at 1 cm coarsened the grid of all),
    # and the interpolation is within about 1e-6 of the force wherever the point lies.
    scene = fitted_scene(result)
    offset = d - delta0
    decade = np.floor(np.log10(np.maximum(np.abs(np.where(finite, offset, 1.0)), _SMALLEST_DEPTH)))
    for g in np.unique(decade[finite]):
        chosen_points = finite & (decade == g)
        depth = 10.0 ** (g + 1)
        sim = simulate(scene, max_indentation=depth, points=4000, free_fraction=1.05, branch=chosen,
                       delta0=delta0, P0=P0)
        x, y = sim.delta, sim.P
        if chosen == "retract":  # retract samples come with delta decreasing
            x, y = x[::-1], y[::-1]
        out[chosen_points] = np.interp(d[chosen_points], x, y, left=P0, right=float(y[-1]))
    return out


# |delta - delta0| below this [m] (a contact point asked for exactly) is evaluated in its decade.
_SMALLEST_DEPTH = 1e-15


def plot(result: Any, ax: Any = None) -> Any:
    """Data, fit and residuals on two axes (matplotlib, imported here); returns the axes."""
    try:
        import matplotlib.pyplot as plt
        from matplotlib.ticker import EngFormatter
    except ImportError:  # pragma: no cover - matplotlib is optional
        raise ImportError("FitResult.plot needs matplotlib (Debian: python3-matplotlib)") from None
    if not result.delta.size:
        raise InputError("FitResult.plot: a batch's results keep no samples; results.plot(k) or results.fit_curve(k) "
                         "fits curve k again with them")
    if ax is None:
        _, (top, bottom) = plt.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    else:
        top = ax
        bottom = ax.inset_axes([0.0, -0.38, 1.0, 0.28], sharex=ax)
    x, P, fit = result.delta, result.P, result.P_fit
    excluded = result.excluded.astype(bool) if result.excluded.size else np.zeros(x.shape, bool)
    kept = ~excluded
    top.plot(x[kept], P[kept], ".", ms=3, label="data")
    if excluded.any():
        top.plot(x[excluded], P[excluded], "x", ms=3, color="0.6", label="excluded")
    top.plot(x, fit, "-", lw=1.5, label="fit (%s)" % result.model)
    top.set_ylabel("P")
    top.legend(loc="best", fontsize="small")
    bottom.plot(x[kept], (P - fit)[kept], ".", ms=2)
    bottom.axhline(0.0, color="0.5", lw=0.8)
    bottom.set_xlabel("delta")
    bottom.set_ylabel("residual")
    # SI prefixes on the ticks (200 pN, 1.5 um), not metres and newtons under a 1e-10 offset.
    for axis, unit in ((top.yaxis, "N"), (bottom.yaxis, "N"), (bottom.xaxis, "m"), (top.xaxis, "m")):
        axis.set_major_formatter(EngFormatter(unit=unit))
    return top, bottom


def html_table(result: Any) -> str:
    """A notebook table: each parameter's value, error and unit, then the fit's state."""
    rows = [(html.escape(name), number(value), number(error, 2), html.escape(_core.unit_of(name.split("[")[0])))
            for name, value, error in zip(result.parameters, result.values.view(np.ndarray),
                                          result.errors.view(np.ndarray))]
    state = "converged" if result.converged else "not converged"
    return table("layerjkr fit: %s, %s after %d iterations, rms residual %.3g N" % (
        result.model, state, result.iterations, result.rms_residual),
        ("parameter", "value", "error", "unit"), rows, result.warnings)