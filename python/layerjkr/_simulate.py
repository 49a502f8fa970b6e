"""Simulating a curve (simulate): the synthetic curve of a scene, at equilibrium or in time, with
the noise, offsets and drag an instrument adds."""
from __future__ import annotations

from typing import Literal, NamedTuple, Optional, Tuple

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import InputError
from ._common import Branch, SceneLike, _integer, _number, _text
from ._html import number, table
from ._scene import _as_scene


class Simulation(NamedTuple):
    """A synthetic curve (:func:`simulate`): float64 arrays in SI units, ``a`` and ``t`` empty
    where not made. ``fit(delta, P, scene, t=t, segment=segment)`` fits it back. ``notes``: what
    the curve's accuracy is where it is not exact (a relaxing medium's estimated error)."""
    t: npt.NDArray[np.float64]
    delta: npt.NDArray[np.float64]
    P: npt.NDArray[np.float64]
    a: npt.NDArray[np.float64]
    segment: npt.NDArray[np.int64]
    source: str
    notes: Tuple[str, ...] = ()

    def __repr__(self) -> str:
        # A summary, not 40 kB of arrays: the samples per segment, the time span, the source.
        names = {0: "approach", 1: "retract", 2: "dwell"}
        labels, counts = np.unique(self.segment, return_counts=True)
        parts = ", ".join("%s %d" % (names.get(int(k), "segment %d" % k), n) for k, n in zip(labels, counts))
        span = ", t %.4g to %.4g s" % (self.t[0], self.t[-1]) if len(self.t) else ""
        radius = ", with a" if len(self.a) else ""
        return "Simulation(%d samples: %s%s%s; %s)" % (len(self.P), parts, span, radius, self.source)

    def _repr_html_(self) -> str:
        names = {0: "approach", 1: "retract", 2: "dwell"}
        rows = []
        for k in np.unique(self.segment):
            m = self.segment == k
            t = self.t[m] if len(self.t) else None
            rows.append((names.get(int(k), "segment %d" % k), int(m.sum()), number(float(self.delta[m].min())),
                         number(float(self.delta[m].max())), number(float(self.P[m].min())), number(float(self.P[m].max())),
                         "-" if t is None else "%s to %s" % (number(float(t[0]), 4), number(float(t[-1]), 4))))
        return table("layerjkr simulation: %d samples%s; %s" % (len(self.P), ", with a" if len(self.a) else "", self.source),
                     ("segment", "samples", "delta min [m]", "delta max [m]", "P min [N]", "P max [N]", "t [s]"), rows,
                     self.notes)


def simulate(scene: SceneLike, *, max_indentation: float, speed: float = 0.0, retract_speed: float = 0.0,
             dwell: float = 0.0, points: int = 500, free_fraction: float = 0.5, noise: float = 0.0, seed: int = 1,
             with_radius: bool = False, branch: Branch = "all", delta0: float = 0.0, P0: float = 0.0,
             control: Literal["grips", "cantilever"] = "grips", stiffness: Optional[float] = None,
             drag: float = 0.0) -> Simulation:
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
        Samples per branch, in [2, 100000].
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
    drag : float, default 0
        The lever's hydrodynamic drag b [N s/m], >= 0 (needs ``speed``): every force gains b v, v
        the base's speed towards the sample (a fit in time frees it as ``"drag"``).

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
    n, seed_ = _integer("points", points), _integer("seed", seed)
    if not 2 <= n <= _core.MAX_POINTS_PER_BRANCH:
        raise InputError("points = %d is invalid; valid range: [2, %d]" % (n, _core.MAX_POINTS_PER_BRANCH))
    if not 0 <= seed_ < 2**64:
        raise InputError("seed = %d is invalid; valid range: [0, 2**64 - 1]" % seed_)
    o = _core.simulation_options(
        max_indentation=_number("max_indentation", max_indentation), speed=_number("speed", speed),
        retract_speed=_number("retract_speed", retract_speed), dwell=_number("dwell", dwell),
        points=n, free_fraction=_number("free_fraction", free_fraction),
        noise=_number("noise", noise), seed=seed_, with_radius=bool(with_radius),
        branch=_text("branch", branch), delta0=_number("delta0", delta0), P0=_number("P0", P0),
        control=_text("control", control), stiffness=0.0 if stiffness is None else _number("stiffness", stiffness),
        drag=_number("drag", drag))
    t, d, p, a, seg, source, notes = _core.simulate(_as_scene(scene), o)
    return Simulation(t, d, p, a, np.asarray(seg, dtype=np.int64), source, tuple(notes))
