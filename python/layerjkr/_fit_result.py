"""What a fit returns: FitResult (values, errors, correlation indexable by name) and NamedArray."""
from __future__ import annotations

import math
from typing import Any, Callable, Dict, List, NamedTuple, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core, _fit_views, _profile
from ._core import Scene
from ._common import _finite_or_none
from ._fit_statistics import STATISTICS_FIELDS, FitStatistics, statistics_dict
from ._named_array import NamedArray
from ._profile import ProfileInterval


class _Parameter(NamedTuple):
    value: float
    standard_error: float
    initial: float
    at_bound: bool
    identifiable: bool
    upper_bound: float
    reason: str


_SUMMARY_FIELDS = ("converged", "termination", "iterations", "model", "family", "rms_residual", "excluded_count",
                   "pull_off_force", "baseline_slope", "baseline_slope_stderr", "baseline_offset", "points",
                   "points_in_contact", "identifiable", "identifiability_known", "identifiability_reason",
                   "identifiability", "unidentifiable", "no_move_reason", "warnings", "notices", "initial_cost",
                   "final_cost", "solve_seconds", "contact_point", "noise", "runs_z", "residual_structure",
                   "force_noise", "radius_noise", "force_noise_given", "radius_noise_given", "displacement_noise",
                   "displacement_noise_given") + STATISTICS_FIELDS


class FitResult(FitStatistics):
    """A fitted curve (the library's FitSummary): estimates with standard errors, their
    covariance and correlation, identifiability, warnings, and the data with the fitted curve.

    ``values``, ``errors``, ``covariance`` and ``correlation`` are :class:`NamedArray`
    indexed by the names in ``parameters``; ``provenance`` says what the fit was made from
    (version, scene, options, the inputs' SHA-256); ``chisqr``, ``redchi``, ``aic``, ``bic``,
    ``ndata`` and ``nvarys`` as lmfit names them. Picklable (plain Python and numpy values)."""

    __slots__ = ("_s", "_f", "_params", "_corr", "_arrays", "_brief_text", "_branch", "_provenance", "_again")

    def __init__(self, s: Any, branch: str,
                 provenance: Union[None, Dict[str, Any], Callable[[], Dict[str, Any]]] = None) -> None:
        # The library's summary is kept and read when a field is first asked for: a map's fit
        # of a few hundred microseconds is not to pay for the fields and arrays no one reads.
        self._s = s
        self._f: Optional[Dict[str, Any]] = None
        self._arrays: Optional[Dict[str, Any]] = None
        self._brief_text: Optional[str] = None
        self._params = {p.name: _Parameter(p.value, p.standard_error, p.initial, p.at_bound, p.identifiable,
                                              p.upper_bound, p.reason)
                        for p in s.parameters}
        self._corr = s.correlation
        self._branch = branch
        self._provenance = provenance if provenance is not None else {}
        self._again: Optional[Callable[..., Any]] = None  # layerjkr.fit's own call, for profile()

    @property
    def _fields(self) -> Dict[str, Any]:
        if self._f is None:
            self._f = {k: getattr(self._s, k) for k in _SUMMARY_FIELDS}
        return self._f

    def _field(self, name: str) -> Any:
        return self._f[name] if self._f is not None else getattr(self._s, name)

    def _array(self, name: str) -> Any:
        if self._arrays is None:
            s = self._s
            self._arrays = {"delta": s.delta, "P": s.P, "P_fit": s.P_fit, "excluded": s.excluded, "t": s.t}
        return self._arrays[name]

    @property
    def _brief(self) -> str:
        if self._brief_text is None:
            self._brief_text = self._s.brief_report()
        return self._brief_text

    def __getstate__(self) -> Any:
        self.provenance  # a record made on demand is made before it travels
        self._fields, self._array("delta"), self._brief  # ...and so is every field read lazily
        return {k: getattr(self, k) for k in self.__slots__ if k not in ("_s", "_again")}

    def __setstate__(self, state: Any) -> None:
        object.__setattr__(self, "_s", None)
        object.__setattr__(self, "_again", None)
        for k, v in state.items():
            object.__setattr__(self, k, v)

    @property
    def delta(self) -> npt.NDArray[np.float64]:
        """The fitted branch's approach samples [m], in acquisition order (empty in a batch)."""
        return self._array("delta")

    @property
    def P(self) -> npt.NDArray[np.float64]:
        """The fitted branch's force samples [N] (empty in a batch)."""
        return self._array("P")

    @property
    def t(self) -> npt.NDArray[np.float64]:
        """A fit in time: each sample's time [s] (aligned with ``delta``); empty otherwise."""
        return self._array("t")

    @property
    def P_fit(self) -> npt.NDArray[np.float64]:
        """The fitted model at the same samples [N] (empty in a batch)."""
        return self._array("P_fit")

    @property
    def excluded(self) -> npt.NDArray[np.bool_]:
        """Per sample: a retract sample after the release that is not JKR (a tail not yet back
        at the baseline), excluded from the fit (empty in a batch)."""
        return self._array("excluded")

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
        return self._field("identifiable")

    @property
    def identifiability_known(self) -> bool:
        """False when identifiability could not be decided (the covariance failed or was not
        computed)."""
        return self._field("identifiability_known")

    @property
    def identifiability_reason(self) -> str:
        """Why the fit is not identifiable, or why that is unknown; empty when identifiable."""
        return self._field("identifiability_reason")

    @property
    def reasons(self) -> Dict[str, str]:
        """Per parameter: why it has no error bar or is not identifiable (empty when it has both)."""
        return {k: p.reason for k, p in self._params.items()}

    @property
    def no_move_reason(self) -> str:
        """Why the solver did not move from its start (empty when it did)."""
        return self._field("no_move_reason")

    @property
    def unidentifiable(self) -> List[str]:
        """The groups of parameters the data cannot separate."""
        return list(self._field("unidentifiable"))

    @property
    def converged(self) -> bool:
        """Whether the solver converged."""
        return self._field("converged")

    @property
    def warnings(self) -> List[str]:
        """The fit's warnings (also emitted as :class:`ModelWarning` by :func:`fit`)."""
        return list(self._field("warnings"))

    @property
    def notices(self) -> List[str]:
        """What the fit records but does not warn about (never a :class:`ModelWarning`): a
        numerical error far below what matters, a documented approximation, a reader's choice."""
        return list(self._field("notices"))

    @property
    def model(self) -> str:
        """The contact model that was fitted."""
        return self._field("model")

    @property
    def family(self) -> str:
        """How the model was evaluated: "foundation", "hertz", "tabulated" or "dugdale"
        (a Dugdale law solved on the medium per parameter vector; docs/fitting.md)."""
        return self._field("family")

    @property
    def iterations(self) -> int:
        """Solver iterations."""
        return self._field("iterations")

    @property
    def termination(self) -> str:
        """The solver's termination message."""
        return self._field("termination")

    @property
    def contact_point(self) -> Dict[str, Any]:
        """The contact point the fit used: ``method``; ``value`` [m] (the fitted delta0 for
        "fit", else the method's point) and ``stderr`` [m] (delta0's standard error, or the
        method's uncertainty; NaN when delta0 was fixed with "fit"); ``baseline`` [N] the
        method found (NaN for "fit"); ``range_reference`` [m], the point the ranges were
        measured from (NaN without a range); ``approach_samples`` and ``samples_in_range``."""
        return dict(self._field("contact_point"))

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
        The nested dicts of a batch's results are shared between them: do not change them.
        Made when first asked for (hashing the inputs cost a fifth of a small fit)."""
        if callable(self._provenance):
            self._provenance = self._provenance()
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
            "rms_residual": f["rms_residual"], "statistics": statistics_dict(f), "excluded": f["excluded_count"],
            "pull_off_force": _finite_or_none(f["pull_off_force"]), "baseline_slope": f["baseline_slope"],
            "baseline_slope_stderr": f["baseline_slope_stderr"], "baseline_offset": f["baseline_offset"],
            "points": f["points"],
            "points_in_contact": f["points_in_contact"], "identifiable": f["identifiable"],
            "identifiability_known": f["identifiability_known"],
            "identifiability_reason": f["identifiability_reason"],
            "unidentifiable": list(f["unidentifiable"]), "no_move_reason": f["no_move_reason"],
            "warnings": list(f["warnings"]), "notices": list(f["notices"]),
            "noise": _noise(f),
            "contact_point": {k: _finite_or_none(v) if isinstance(v, float) else v
                              for k, v in f["contact_point"].items()},
        }

    @property
    def scene(self) -> Scene:
        """The fit's scene with the fitted values in place: a model again, for :func:`curve`,
        :func:`summary` and :func:`simulate` (delta0 and P0 belong to the data and stay out).
        Raises InputError for a scene built in code (no JSON to put the values in)."""
        return _fit_views.fitted_scene(self)

    def eval(self, delta: npt.ArrayLike, *, branch: Optional[str] = None) -> npt.NDArray[np.float64]:
        """The fitted force [N] at approaches ``delta`` [m] (delta0 and P0 applied) on ``branch``
        ("approach" or "retract"; default the fit's), from the fitted scene's curve under fixed
        grips (:func:`simulate`) of 4000 samples to the decade of each point's own indentation:
        no point's value depends on the others (within ~1e-6 of the force). NaN in, NaN out. A
        fit in time raises InputError: its force depends on the history."""
        return _fit_views.evaluate(self, delta, branch)

    def plot(self, ax: Any = None) -> Any:
        """Data, fit and residuals (excluded samples marked) with matplotlib, imported on
        first use; ``ax`` draws into given axes (residuals in an inset below). Returns the
        (curve, residual) axes."""
        return _fit_views.plot(self, ax)

    def profile(self, name: str, sigmas: float = 1.0) -> "ProfileInterval":
        """The profile (likelihood) interval of free parameter ``name``: where chi-square, with
        ``name`` held and the other free parameters refitted, rises by ``sigmas``^2 reduced
        chi-squares (lmfit's conf_interval, iminuit's minos). It follows a curved objective
        where the symmetric error bar cannot; an end at the parameter's domain (w = 0) is
        flagged. Ends to 1e-3 of the standard error, about 20-40 refits. Only for results of
        :func:`fit` (not batches, joint fits or unpickled results); delta0 and P0 belong to the
        data and are refused (InputError)."""
        return _profile.profile(self, name, sigmas)

    def _repr_html_(self) -> str:
        return _fit_views.html_table(self)

    def __repr__(self) -> str:
        return "layerjkr.FitResult(%s)" % ", ".join(
            "%s=%.6g+-%.2g" % (k, p.value, p.standard_error) for k, p in self._params.items())


def _noise(f: Any) -> Optional[Dict[str, Any]]:
    """The columns' noises the residuals were weighed by, as the CLI's report gives them."""
    if math.isfinite(f["radius_noise"]):
        return {"P": f["force_noise"], "P_given": f["force_noise_given"], "a": f["radius_noise"],
                "a_given": f["radius_noise_given"]}
    if math.isfinite(f["displacement_noise"]):
        return {"P": f["force_noise"], "P_given": f["force_noise_given"], "delta": f["displacement_noise"],
                "delta_given": f["displacement_noise_given"]}
    return None
