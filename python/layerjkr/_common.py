"""Shared helpers of the package: the argument checks every call uses, the type aliases of its
signatures and ModelWarning. Internal; the public names are re-exported by layerjkr."""
from __future__ import annotations

import os
import warnings as _warnings
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._core import InputError, Scene


SceneLike = Union[Scene, Dict[str, Any], str, "os.PathLike[str]"]
Branch = Literal["approach", "retract", "all", "dwell", "approach_dwell"]
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


def _positive(name: str, value: Any, unit: str) -> float:
    """A finite number > 0 for argument ``name`` [unit], else InputError naming it and the range
    (rather than the library's name for the quantity)."""
    v = _number(name, value)
    if not (np.isfinite(v) and v > 0):
        raise InputError("%s = %r is invalid; valid range: finite and > 0 [%s]" % (name, value, unit))
    return v


def _integer(name: str, value: Any) -> int:
    """An integer for option ``name``: 2.5 is refused rather than truncated, and one the library's
    32-bit integers cannot hold is an InputError naming it (not the binding's TypeError)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError("%s must be an integer, got %s %r" % (name, type(value).__name__, value))
    if not -2**31 <= int(value) < 2**31:
        raise InputError("%s = %d is out of range; valid range: [%d, %d]" % (name, int(value), -2**31, 2**31 - 1))
    return int(value)


def _sequence(name: str, value: Any) -> Sequence[Any]:
    """A list from a sequence for argument ``name``, else TypeError naming it."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise TypeError("%s must be a sequence, got %s %r" % (name, type(value).__name__, value))
    return list(value)


def _pairs(name: str, value: Any) -> Sequence[Any]:
    """A list of (x, y) pairs for argument ``name``, else TypeError naming it and the bad element."""
    items = _sequence(name, value)
    for k, item in enumerate(items):
        if isinstance(item, (str, bytes)) or not hasattr(item, "__len__") or len(item) != 2:
            raise TypeError("%s[%d] must be a pair (delta, P), got %s %r" % (name, k, type(item).__name__, item))
    return items


def _path(name: str, value: Any) -> str:
    """A file system path (str, bytes or os.PathLike) as str, else TypeError naming ``name``; bytes
    that are not UTF-8 keep their bytes through os.fsdecode's surrogates."""
    if not isinstance(value, (str, bytes, os.PathLike)):
        raise TypeError("%s must be a path (str, bytes or os.PathLike), got %s %r" % (name, type(value).__name__, value))
    return os.fsdecode(value)


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
        if (isinstance(v, bool) or not isinstance(v, (int, float)) or abs(v) >= 2**31 or not np.isfinite(v)
                or v != int(v)):
            raise InputError("segment[%d] = %r is not a segment label; valid values: 0 (approach), 1 (retract), 2 (dwell)" % (i, v))
        out.append(int(v))
    return np.array(out, dtype=np.int64)


def _warn(messages: Sequence[str], stacklevel: int) -> None:
    for message in messages:
        _warnings.warn(message, ModelWarning, stacklevel=stacklevel + 1)


def _finite_or_none(x: Optional[float]) -> Optional[float]:
    return x if x is not None and np.isfinite(x) else None


def _float64(a: npt.ArrayLike, name: str = "array") -> npt.NDArray[np.float64]:
    """The float64 C-ordered array the library fits (and provenance hashes); what cannot be one is
    a TypeError naming the argument."""
    try:
        return np.asarray(a, dtype=np.float64, order="C")
    except (TypeError, ValueError) as e:
        raise TypeError("%s must be an array of numbers, got %s: %s" % (name, type(a).__name__, e)) from None
