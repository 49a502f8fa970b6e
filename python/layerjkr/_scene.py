"""Scenes: layerjkr.scene() and the small answers that describe a scene's model (AutoChoice,
FixedGrips, AdhesionCheck, ModelError)."""
from __future__ import annotations

import html
import json
import os
from typing import Any, Callable, NamedTuple, Optional

import numpy as np

from . import _core
from ._core import InputError, Scene
from ._common import SceneLike, _json_value
from ._html import number, table


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
def _scene_html(self: Scene) -> str:
    """A notebook view of a scene: every value of its JSON, by key path (medium.E, w, ...)."""
    rows = []

    def walk(prefix: str, value: Any) -> None:
        if isinstance(value, dict):
            for k, v in value.items():
                walk("%s.%s" % (prefix, k) if prefix else k, v)
        else:
            rows.append((html.escape(prefix), number(value) if isinstance(value, (int, float)) and
                         not isinstance(value, bool) else html.escape(json.dumps(value))))

    try:
        walk("", json.loads(self.json) if self.json else {})
    except ValueError:
        pass
    return table("layerjkr scene: model %s, %s" % (self.model, self.profile), ("key", "value"), rows)


Scene._repr_html_ = _scene_html  # the compiled class takes a Python method for notebooks

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
