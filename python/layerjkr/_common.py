"""Shared helpers of the package: the argument checks every call uses, the type aliases of its
signatures and ModelWarning. Internal; the public names are re-exported by layerjkr."""
from __future__ import annotations

import os  # noqa: F401 - named in SceneLike
import warnings as _warnings
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._core import InputError, Scene


SceneLike = Union[Scene, Dict[str, Any], str, "os.PathLike[str]"]
Branch = Literal["approach", "retract", "all"]
Control = Literal["auto", "load", "cantilever", "grips"]
BaselineKind = Literal["constant", "tilt"]
Window = Literal["all", "pull_off", "fraction"]
Loss = Literal["none", "huber", "cauchy"]
ContactPointMethod = Literal["fit", "threshold", "rov", "gof"]
CurveRangeLike = Union[slice, Tuple[int, int]]


class ModelWarning(UserWarning):
    """An answer the library warns about: a model estimated to be off its reference by more
    than the warning threshold, or constants outside a model's validity. The same text is in
    the answer's ``warnings`` list."""


def _number(name: str, value: Any) -> float:
    """A real number for option ``name``, else TypeError naming it (not a bare conversion error)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError("%s must be a number, got %s %r" % (name, type(value).__name__, value))
    return float(value)


def _integer(name: str, value: Any) -> int:
    """An integer for option ``name``: 2.5 is refused rather than truncated."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError("%s must be an integer, got %s %r" % (name, type(value).__name__, value))
    return int(value)


def _text(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError("%s must be a string, got %s %r" % (name, type(value).__name__, value))
    return value


def _json_value(value: Any) -> Any:
    """numpy scalars and arrays in a scene dict as the JSON numbers and lists they hold."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError("scene: a value of type %s cannot be written as JSON" % type(value).__name__)


def _segments(segment: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """Segment labels 0, 1 or 2 as an int64 array; a non-integer label (0.5) is refused with its
    value, not cast. The library checks that each label is 0, 1 or 2.

    Vectorised for numeric arrays (a Python loop over a curve's labels cost three times the fit
    itself, and a list's conversion to the library a tenth of it); other inputs are checked label
    by label."""
    values = np.asarray(segment).ravel()
    if values.dtype.kind == "i" or (values.dtype.kind == "u" and (values.size == 0 or values.max() < 2**31)):
        return values.astype(np.int64)
    if values.dtype.kind == "f":
        bad = ~np.isfinite(values)
        bad[~bad] = (values[~bad] != np.floor(values[~bad])) | (np.abs(values[~bad]) >= 2**31)
        if not bad.any():
            return values.astype(np.int64)
    out = []
    for i, v in enumerate(values.tolist()):
        if (isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v) or v != int(v)
                or abs(v) >= 2**31):
            raise InputError("segment[%d] = %r is not a segment label; valid values: 0 (approach), 1 (retract), 2 (dwell)" % (i, v))
        out.append(int(v))
    return np.array(out, dtype=np.int64)


def _warn(messages: Sequence[str], stacklevel: int) -> None:
    for message in messages:
        _warnings.warn(message, ModelWarning, stacklevel=stacklevel + 1)


def _finite_or_none(x: Optional[float]) -> Optional[float]:
    return x if x is not None and np.isfinite(x) else None


def _float64(a: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The float64 C-ordered array the library fits (and provenance hashes)."""
    return np.asarray(a, dtype=np.float64, order="C")
