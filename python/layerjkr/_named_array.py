"""NamedArray: a read-only float64 array of fit quantities indexed by parameter name as well as by
position (FitResult.values, errors, correlation, covariance)."""
from __future__ import annotations

from typing import Any, Dict, Sequence, Tuple

import numpy as np
import numpy.typing as npt


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

    def __str__(self) -> str:
        """Labelled: ``E = 1.99972e+04`` lines, or a matrix with its names on both sides."""
        m = self.view(np.ndarray)
        if self.ndim == 1 and len(self._names) == m.size:
            width = max((len(n) for n in self._names), default=0)
            return "\n".join("%-*s = %.6g" % (width, n, float(v)) for n, v in zip(self._names, m))
        if self.ndim == 2 and m.shape == (len(self._names),) * 2:
            width = max(max((len(n) for n in self._names), default=0), 9)
            head = " " * width + "".join(" %9s" % n[:9] for n in self._names)
            return "\n".join([head] + ["%-*s" % (width, a) + "".join(" %9.3f" % float(v) for v in m[i])
                                        for i, a in enumerate(self._names)])
        return str(m)

    def __repr__(self) -> str:
        if self.ndim == 1:
            return "NamedArray({%s})" % ", ".join("%r: %r" % (n, float(v)) for n, v in zip(self._names, self.view(np.ndarray)))
        return "NamedArray(%s, names=%r)" % (np.array2string(self.view(np.ndarray), separator=", "), self._names)
