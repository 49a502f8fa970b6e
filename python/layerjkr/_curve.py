"""The adhesive curve of a scene over contact radii: layerjkr.curve() and its Curve."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from . import _core
from ._common import SceneLike, _number, _warn
from ._html import number, table
from ._scene import AutoChoice, _as_scene, _choice


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

    def _repr_html_(self) -> str:
        # The first and last rows, as pandas shows a long frame, and the warnings.
        n = len(self)
        shown = list(range(n)) if n <= 10 else list(range(5)) + [-1] + list(range(n - 5, n))
        columns = ("a", "P", "delta", "S", "error_est")
        rows = [("...",) * len(columns) if i < 0 else tuple(number(float(getattr(self, c)[i])) for c in columns)
                for i in shown]
        return table("layerjkr curve: model %s (reference %s), %d radii" % (self._model, self.reference or "-", n),
                     ("a [m]", "P [N]", "delta [m]", "S [N/m]", "error_est"), rows, self._warnings)


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
