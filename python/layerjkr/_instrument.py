"""Instrument files (JPK, Asylum/Igor, NanoScope): read_instrument and open_instrument."""
from __future__ import annotations

import os
import sys
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union, overload

from . import _core
from ._core import InputError
from ._common import CurveRangeLike, _integer, _number, _path, _positive


# CurveRange's "to the last curve" as the binding takes it: any end past the last curve stops
# there, and sys.maxsize fits a size_t on every platform.
_NO_END = sys.maxsize


def _curve_range(curves: Any) -> Tuple[int, Optional[int]]:
    """``curves`` as (begin, end or None): positions in file order, as the CLI's --curves A:B.

    Negative bounds are refused rather than counted from the end: that would need the file's
    length before reading, and a range is meant to name the same curves in every file."""
    if isinstance(curves, slice):
        if curves.step is not None and curves.step != 1:
            raise InputError("curves = %r: a step of %r; a range of curves is contiguous (step 1)" % (curves, curves.step))
        start, stop = curves.start, curves.stop
    elif isinstance(curves, tuple) and len(curves) == 2:
        start, stop = curves
        if start is None or stop is None:
            raise TypeError("curves = %r: a pair needs two integers (begin, end); use a slice for an open end" % (curves,))
    else:
        raise TypeError("curves must be a slice or a pair of integers (begin, end), got %s %r"
                        % (type(curves).__name__, curves))
    begin = 0 if start is None else _integer("curves begin", start)
    end = None if stop is None else _integer("curves end", stop)
    if begin < 0 or (end is not None and end < 0):
        raise InputError("curves = %r: positions are >= 0 (counted from the file's first curve, not its end)" % (curves,))
    if end is not None and begin > end:
        raise InputError("curves = %r: begin %d is after end %d" % (curves, begin, end))
    return begin, end


def read_instrument(path: Union[str, "os.PathLike[str]"], *, curves: Optional[CurveRangeLike] = None,
                    spring_constant: Optional[float] = None, sensitivity: Optional[float] = None) -> List[Dict[str, Any]]:
    """The curves of an instrument file, or of a range of its curves.

    Parameters
    ----------
    path : str or os.PathLike
        A JPK (.jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series), Igor (.ibw), Bruker NanoScope
        (.spm, .000 - .999) or AFM Workshop map (.zip) file.
    curves : slice or (int, int), optional
        Read only the curves at these positions (0-based, file order): ``slice(a, b)`` or
        ``(a, b)`` for a .. b - 1, ``slice(a, None)`` for a to the end; as list slicing, an
        end past the last curve stops there. Only the range is read from the file. None:
        every curve.
    spring_constant : float, optional
        The cantilever's spring constant [N/m]: replaces the file's, or gives one it lacks
        (a JPK file whose force conversion is not defined; an Asylum map without its image).
    sensitivity : float, optional
        The deflection sensitivity [m/V]: replaces the file's (the deflection rescales), or
        gives one it lacks (a JPK calibration force-save, whose deflection is in volts).

    Returns
    -------
    list of dict
        Per curve: delta (= -tip position) [m] and P [N] as float64 arrays, segment (0
        approach, 1 retract, 2 dwell), t [s] (each sample's time from the segments' durations, as
        ``layerjkr export`` writes it; None where the file gives none), index (the curve's number
        in the file), spring_constant [N/m],
        sensitivity, x, y [m], grid_x, grid_y. ``read_instrument(p, curves=(a, b))`` equals
        ``read_instrument(p)[a:b]``.

    Raises
    ------
    InputError
        A file that cannot be read or parsed (the message names it); a ``curves`` range with
        a step other than 1, a negative bound or its begin after its end (InputError is a
        ValueError).
    TypeError
        A ``curves`` that is not a slice or a pair of integers.

    See Also
    --------
    open_instrument : random access to any curve without reading the others.
    """
    begin, end = (0, None) if curves is None else _curve_range(curves)
    k = 0.0 if spring_constant is None else _positive("spring_constant", spring_constant, "N/m")
    s = 0.0 if sensitivity is None else _positive("sensitivity", sensitivity, "m/V")
    return _core.read_instrument(_path("path", path), begin, end, k, s)


class Instrument(Sequence[Dict[str, Any]]):
    """An instrument file opened for random access: ``open_instrument(path)``.

    Opening reads the header and the index of the curves, never the samples; ``f[i]`` then
    reads curve i alone and ``f[a:b]`` the curves a .. b - 1 (any step), each as the dict
    :func:`read_instrument` returns, with the GIL released. Reads from several threads at
    once are safe. Use it as a context manager, or :meth:`close` it, to release the file.

    Attributes
    ----------
    header : dict
        The file's metadata: path, format ("jpk-force", "jpk-force-map", "jpk-qi-data", "jpk-qi-series",
        "ibw", "nanoscope", "ibw-map", "afm-workshop-map"), instrument, software, grid_shape (x, y; (0, 0) if not a map),
        grid_size (x, y) [m], grid_center (x, y) [m].
    """

    def __init__(self, path: Union[str, "os.PathLike[str]"]) -> None:
        self._reader = _core.InstrumentReader(_path("path", path))
        self._header: Dict[str, Any] = self._reader.header
        self._size: int = len(self._reader)

    @property
    def header(self) -> Dict[str, Any]:
        return dict(self._header)  # a copy: the caller may change it

    @property
    def path(self) -> str:
        return str(self._header["path"])

    @property
    def closed(self) -> bool:
        return bool(self._reader.closed)

    def __len__(self) -> int:
        return self._size

    def _position(self, i: Any) -> int:
        k = _integer("curve position", i)
        if k < 0:
            k += self._size  # a sequence's negative index: the file's length is known here
        if not 0 <= k < self._size:
            raise IndexError("curve position %d is outside %s's %d curves" % (i, self.path, self._size))
        return k

    @overload
    def __getitem__(self, key: int) -> Dict[str, Any]: ...

    @overload
    def __getitem__(self, key: slice) -> List[Dict[str, Any]]: ...

    def __getitem__(self, key: Union[int, slice]) -> Union[Dict[str, Any], List[Dict[str, Any]]]:
        if isinstance(key, slice):
            return list(self._reader.curves(list(range(*key.indices(self._size)))))
        return dict(self._reader.curves([self._position(key)])[0])

    def curve_number(self, i: int) -> int:
        """The number curve ``i`` carries in the file (JPK's index/N, else its position),
        without reading the curve."""
        return int(self._reader.curve_number(self._position(i)))

    def close(self) -> None:
        """Releases the file; reads after it raise ValueError (the header stays readable)."""
        self._reader.close()

    def __enter__(self) -> "Instrument":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __reduce__(self) -> Any:
        # Pickled as its path (Dask ships it to a worker, which opens the file itself).
        return (open_instrument, (self.path,))

    def __repr__(self) -> str:
        h = self._header
        grid = " on a %dx%d grid" % tuple(h["grid_shape"]) if h["grid_shape"][0] > 0 else ""
        return "<layerjkr.Instrument %r: %s, %d curves%s%s>" % (self.path, h["format"], self._size, grid,
                                                               " (closed)" if self.closed else "")


def open_instrument(path: Union[str, "os.PathLike[str]"]) -> Instrument:
    """Opens an instrument file for random access to its curves.

    Parameters
    ----------
    path : str or os.PathLike
        A JPK (.jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series), Igor (.ibw), Bruker NanoScope
        (.spm, .000 - .999) or AFM Workshop map (.zip) file.

    Returns
    -------
    Instrument
        ``len(f)`` curves; ``f[i]``, ``f[a:b]`` read them (the dicts of
        :func:`read_instrument`), ``f.header`` the metadata, ``f.curve_number(i)`` the number
        curve i carries. Only the header and the index are read here (a 65 536-curve QI map
        opens in about 0.6 s), so splitting a map into ranges starts cheaply:
        ``n = len(layerjkr.open_instrument(path))``.

    Raises
    ------
    InputError
        A missing file, one of no known format, or a header that cannot be read (named).

    Examples
    --------
    >>> with layerjkr.open_instrument("map.jpk-qi-data") as f:  # doctest: +SKIP
    ...     first, last = f[0], f[-1]
    ...     some = f[100:200]          # == layerjkr.read_instrument(path, curves=(100, 200))
    """
    return Instrument(path)
