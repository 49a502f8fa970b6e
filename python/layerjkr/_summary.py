"""The summary of a scene (pull-off, zero load, fixed grips, checks): layerjkr.summary() and Summary."""
from __future__ import annotations

from typing import Any, Dict, List, NamedTuple, Optional, Tuple

from . import _core
from ._core import InputError
from ._common import SceneLike, _finite_or_none, _number, _positive, _warn
from ._html import number, table
from ._scene import AdhesionCheck, AutoChoice, FixedGrips, ModelError, _as_scene, _choice


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
                "rate_ratio": k["rate_ratio"], "regime": k["regime"],
                "rate_dependence": [{"rate": float(r), "pull_off_force": _finite_or_none(float(f))}
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

    def _repr_html_(self) -> str:
        d = self.as_dict()
        fg = d["fixed_grips_critical"] or {}
        err = d["model_error_estimate"]
        rows = [("pull-off force", number(d["pull_off_force"]), "N"), ("pull-off radius", number(d["pull_off_radius"]), "m"),
                ("zero-load radius", number(d["zero_load_radius"]), "m"),
                ("fixed grips: force", number(fg.get("force")), "N"), ("fixed grips: radius", number(fg.get("radius")), "m"),
                ("model error: pull-off force", number(err["pull_off_force"], 3), "against %s" % (err["reference"] or "-")),
                ("model error: zero-load radius", number(err["zero_load_radius"], 3), "against %s" % (err["reference"] or "-"))]
        rows += [(k, number(d[k]), unit) for k, unit in (("K", "N/m^3"), ("G", "N/m"), ("T", "N/m"), ("E_star", "Pa"))
                 if k in d]
        return table("layerjkr summary: model %s, %s, w = %s J/m^2" % (self.model, self.profile, number(self.w)),
                     ("quantity", "value", "unit"), rows, self.warnings)


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
                                   0.0 if rate is None else (_positive("retract_speed", rate, "m/s") if load_rate is None
                                                             else _positive("load_rate", rate, "N/s")),
                                   0.0 if stiffness is None else _positive("stiffness", stiffness, "N/m"),
                                   _number("start_force", start_force)))
    _warn(result._a.warnings, 2)
    return result
