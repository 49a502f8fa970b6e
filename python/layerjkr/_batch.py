"""Fitting many curves: fit_batch (arrays) and fit_files (CSV and instrument files, maps, reports)."""
from __future__ import annotations

import contextlib
import os
import tempfile
import warnings as _warnings
from typing import Any, Callable, Dict, Iterator, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy.typing as npt

from . import _core
from ._core import InputError
from ._common import ModelWarning
from ._common import BaselineKind, Branch, ContactPointMethod, Control, CurveRangeLike, Loss, SceneLike, Window, _float64, _integer, _number, _pairs, _path, _positive, _sequence, _text
from ._scene import _as_scene
from ._fit_result import FitResult
from ._fit_options import _array_inputs, _options, _provenance, _with_fit_parameters, _with_inputs
from ._instrument import _NO_END, _curve_range
from ._batch_tables import BatchResults


class BatchResult(NamedTuple):
    """One curve of :func:`fit_batch` or :func:`fit_files`: its fit, or why it failed."""

    source: str
    """The file name, or "curve N" in a batch of arrays."""
    curve: Optional[int]
    """The curve's number in an instrument file, else None."""
    x: float
    """Map position [m] (NaN where the file has none)."""
    y: float
    """Map position [m] (NaN where the file has none)."""
    grid_x: Optional[int]
    """Grid pixel (None where the file has none)."""
    grid_y: Optional[int]
    """Grid pixel (None where the file has none)."""
    result: Optional[FitResult]
    """The fit (without the per-sample arrays), or None if it failed."""
    error: Optional[str]
    """The library's message if the curve could not be read or fitted, else None."""

    @property
    def ok(self) -> bool:
        """True if the curve was fitted."""
        return self.result is not None


def _say_failures(items: Sequence[Any], stacklevel: int) -> None:
    """A batch goes on past a bad curve or file, and says so: a ModelWarning counting the failures
    and naming the first (every curve failing - a wrong scene, a wrong unit - is the loud case)."""
    failed = [it for it in items if not it.ok]
    if not failed:
        return
    error = failed[0].error
    first = error if error.startswith(failed[0].source) else "%s: %s" % (failed[0].source, error)
    if len(failed) == len(items):
        message = "every curve of the batch failed (%d of %d); the first: %s" % (len(failed), len(items), first)
    else:
        message = "%d of %d curves failed (their items have .error); the first: %s" % (len(failed), len(items), first)
    _warnings.warn(message, ModelWarning, stacklevel=stacklevel + 1)


def _batch(items: Sequence[Any], branch: str,
           provenance: Optional[Callable[[int, Any], Dict[str, Any]]] = None,
           refit: Optional[Callable[[int], Any]] = None) -> BatchResults:
    _say_failures(items, stacklevel=3)
    out = []
    for k, it in enumerate(items):
        record = provenance(k, it) if provenance is not None and it.ok else None
        out.append(BatchResult(source=it.source, curve=it.curve if it.curve >= 0 else None, x=it.x, y=it.y,
                               grid_x=it.grid_x if it.grid_x >= 0 else None, grid_y=it.grid_y if it.grid_y >= 0 else None,
                               result=FitResult(it.summary, branch, record) if it.ok else None,
                               error=None if it.ok else it.error))
    return BatchResults(out, [it.quality for it in items], refit)


def _item_path(it: Any) -> bytes:
    """The file an item was read from: its source without the "#curve" a map's pixel carries."""
    suffix = "#%d" % it.curve
    source = it.source[:-len(suffix)] if it.curve >= 0 and it.source.endswith(suffix) else it.source
    return os.fsencode(source)


# Every sample a re-read curve keeps (a batch keeps none; a report thins them).
_ALL_SAMPLES = 2 ** 62


@contextlib.contextmanager
def _keep_finished(branch: str) -> Iterator[None]:
    # _core attaches the finished items to the exception that a signal handler raised.
    try:
        yield
    except BaseException as e:
        items = getattr(e, "batch_items", None)
        if items is not None:
            e.results = _batch(items, branch)  # type: ignore[attr-defined]
            del e.batch_items  # type: ignore[attr-defined]
        raise


def fit_batch(curves: Sequence[Tuple[npt.ArrayLike, npt.ArrayLike]], scene: SceneLike, *,
              free: Union[str, Sequence[str]] = ("E", "w", "delta0", "P0"), jobs: int = 1, branch: Branch = "approach",
              control: Control = "auto", spring_constant: Optional[float] = None,
              baseline: BaselineKind = "constant", window: Window = "all", window_fraction: float = 0.5,
              loss: Loss = "none", loss_scale: Optional[float] = None, starts: int = 0,
              max_iterations: int = 200,
              contact_point: ContactPointMethod = "fit", indentation_range: Optional[Tuple[float, float]] = None,
              force_range: Optional[Tuple[float, float]] = None,
              baseline_window: Optional[Tuple[float, float]] = None,
              report: Optional[Union[str, "os.PathLike[str]"]] = None) -> BatchResults:
    """Fit many curves with the same scene and options on ``jobs`` threads.

    Parameters
    ----------
    curves : sequence of (delta, P)
        Each a pair of 1-D arrays [m], [N] (split at their largest delta).
    scene : Scene, dict or path
        See :func:`scene`.
    jobs : int, default 1
        Worker threads, >= 1 (the GIL is released).
    %s
    report : path, optional
        Also write the interactive report (as ``fit-map --report``; see :func:`fit_files`)
        to ``report/index.html``; the curves, having no map position, are laid out by index.

    Returns
    -------
    BatchResults
        A list of BatchResult (with ``to_pandas``, ``image``, ``to_xarray``, ``to_tiff``), one per curve, in order: its FitResult (without the per-sample arrays, or with
        ``report``, with the thinned ones the report shows) or the error message. A curve that
        cannot be fitted never stops the batch. The fits' warnings are in each result, not
        emitted.

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C (checked every 0.1 s): no further curve starts, the running fits finish,
        and the exception's ``results`` holds the finished curves (a prefix of the input, as
        BatchResults). The same for any exception a signal handler raises.
    InputError
        An invalid option (named), ``jobs`` < 1, an array not 1-D.
    DomainError
        An option outside its range.
    TypeError
        An unknown keyword.
    """
    options = _options(free, branch, control, spring_constant, baseline, window, window_fraction, loss, loss_scale,
                       starts, max_iterations, contact_point, indentation_range, force_range, baseline_window)
    pairs = [(_float64(c[0], "curves[%d] delta" % k), _float64(c[1], "curves[%d] P" % k))
             for k, c in enumerate(_pairs("curves", curves))]
    s = _as_scene(scene)
    directory = _report_dir(report)
    with _keep_finished(options.branch):
        items = _core.fit_batch(pairs, s, options, _integer("jobs", jobs),
                                _core.DEFAULT_DISPLAY_POINTS if directory else 0)
    if directory:
        _write_report(items, options, directory, "%d curves (fit_batch)" % len(items))
    base = _provenance(s, options, None, [])

    records: Dict[int, Dict[str, Any]] = {}  # made once, as the batch is returned

    def record(k: int, it: Any) -> Dict[str, Any]:
        return records.setdefault(k, _with_inputs(base, _array_inputs(*pairs[k], None)))

    def refit(k: int) -> FitResult:  # the caller's arrays, fitted again alone
        return FitResult(_core.fit(pairs[k][0], pairs[k][1], None, None, s, options), options.branch,
                         record(k, items[k]))

    return _batch(items, options.branch, record, refit)


_with_fit_parameters(fit_batch)


def fit_files(paths: Union[str, "os.PathLike[str]", Sequence[Union[str, "os.PathLike[str]"]]], scene: SceneLike, *,
              free: Union[str, Sequence[str]] = ("E", "w", "delta0", "P0"), jobs: int = 1, branch: Branch = "approach",
              control: Control = "auto", spring_constant: Optional[float] = None, sensitivity: Optional[float] = None,
              baseline: BaselineKind = "constant", window: Window = "all", window_fraction: float = 0.5,
              loss: Loss = "none", loss_scale: Optional[float] = None, starts: int = 0, max_iterations: int = 200,
              units: str = "m,N", z_sign: float = 1.0, deflection_sign: float = 1.0,
              curve: Optional[int] = None, curves: Optional[CurveRangeLike] = None,
              contact_point: ContactPointMethod = "fit", indentation_range: Optional[Tuple[float, float]] = None,
              force_range: Optional[Tuple[float, float]] = None,
              baseline_window: Optional[Tuple[float, float]] = None,
              report: Optional[Union[str, "os.PathLike[str]"]] = None) -> BatchResults:
    """Fit CSV and instrument files on ``jobs`` threads, as ``layerjkr fit-map``.

    Parameters
    ----------
    paths : path or sequence of paths
        CSV files and instrument files (.jpk-force, .jpk-force-map, .jpk-qi-data, .ibw); every
        curve of a map is its own item.
    scene : Scene, dict or path
        See :func:`scene`.
    jobs : int, default 1
        Worker threads, >= 1 (the GIL is released).
    %s
    sensitivity : float, optional
        Instrument files: the deflection sensitivity [m/V] replacing the file's (the deflection
        rescales), or giving one it lacks (a JPK calibration force-save, in volts).
    units : str, default "m,N"
        Units of the CSV files, "LENGTH,FORCE", e.g. "nm,nN".
    z_sign : float, default 1.0
        Raw z,deflection CSV: +1 if z grows towards the sample, -1 if it decreases.
    deflection_sign : float, default 1.0
        Raw z,deflection CSV: +1 if a deflection > 0 means repulsion, else -1.
    curve : int, optional
        Which curve of a CSV export holding several.
    curves : slice or (int, int), optional
        Fit only the curves at these positions of each instrument file (0-based, file order,
        as ``fit-map --curves A:B``): ``slice(a, b)`` or ``(a, b)`` for positions a .. b - 1,
        ``slice(a, None)`` for a to the end. Only those curves are read. A range that selects
        no curve of a file is that file's failed item. CSV files are unaffected. None: every
        curve.
    report : path, optional
        A directory for the interactive report, as ``layerjkr fit-map --report``: one
        self-contained page, ``report/index.html``, that works from file:// without network
        (a heat map per fitted field with colour bar and histogram, bad pixels marked, a
        status filter, each curve with its fit; docs/report.md). The directory is created; an
        existing one must be empty or hold an earlier report (only its index.html), checked
        before any fitting. Not written if the batch is interrupted.

    ``spring_constant`` is also the one the CSV reader uses for z,deflection data and that
    replaces an instrument file's own.

    Returns
    -------
    BatchResults
        A list of BatchResult (with ``to_pandas``, ``image``, ``to_xarray``, ``to_tiff``), one per curve, in file order, with its map position and pixel: its FitResult
        (without the per-sample arrays, or with ``report``, with the thinned ones the report
        shows) or the error message. A file that cannot be read is
        one failed item (so is a path that is not a regular file: a directory, a FIFO, a
        dangling or looping link, never opened). The fits' warnings are in each result, not
        emitted.

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C (checked every 0.1 s): no further curve starts, the running fits finish,
        and the exception's ``results`` holds the finished curves (a prefix of the input, as
        BatchResults). The same for any exception a signal handler raises.
    InputError
        An invalid option (named), unknown units, ``jobs`` < 1; a ``curves`` range with a
        step other than 1, a negative bound or its begin after its end; a ``report`` that is a
        file, cannot be created or written, or is a directory holding other files.
    DomainError
        An option outside its range.
    TypeError
        An unknown keyword; a ``curves`` that is not a slice or a pair of integers.
    """
    options = _options(free, branch, control, spring_constant, baseline, window, window_fraction, loss, loss_scale,
                       starts, max_iterations, contact_point, indentation_range, force_range, baseline_window)
    selection = None
    if curves is not None:
        begin, end = _curve_range(curves)
        selection = (begin, _NO_END if end is None else end)
    csv = _core.csv_options(units=_text("units", units),
                            spring_constant=None if spring_constant is None else _positive("spring_constant", spring_constant, "N/m"),
                            sensitivity=None if sensitivity is None else _positive("sensitivity", sensitivity, "m/V"),
                            z_sign=_number("z_sign", z_sign), deflection_sign=_number("deflection_sign", deflection_sign),
                            curve=None if curve is None else _integer("curve", curve))
    if isinstance(paths, (str, bytes, os.PathLike)):
        paths = [paths]
    paths = [_path("paths[%d]" % k, p) for k, p in enumerate(_sequence("paths", paths))]
    for k, p in enumerate(paths):  # a name that is nothing is the caller's error, not a failed curve
        if not os.path.lexists(p):
            raise InputError("paths[%d] = %r: no such file or directory" % (k, p))
    # As bytes, the file system's own names: a name that is not UTF-8 (os.listdir gives it with
    # surrogates) reaches the file; each result's source gives it back as os.fsdecode would.
    names = [os.fsencode(p) for p in paths]
    s = _as_scene(scene)
    directory = _report_dir(report)
    # Each file hashed once, before it is read (a FIFO or a directory is recorded, not opened).
    hashed = {name: _core.record_file(name) for name in names}
    with _keep_finished(options.branch):
        items = _core.fit_files(names, s, options, csv, _integer("jobs", jobs), selection,
                                _core.DEFAULT_DISPLAY_POINTS if directory else 0)
    if directory:
        _write_report(items, options, directory, "%d input file(s) (fit_files)" % len(names))
    base = _provenance(s, options, csv, [])

    records: Dict[int, Dict[str, Any]] = {}  # made once, as the batch is returned; a refit reuses them

    def record(k: int, it: Any) -> Dict[str, Any]:
        if k not in records:
            path = _item_path(it)
            records[k] = _with_inputs(base, [hashed.get(path) or _core.record_file(path)])
        return records[k]

    def refit(k: int) -> FitResult:  # the curve read again from its file, checked unchanged, fitted alone
        it, path = items[k], _item_path(items[k])
        recorded = record(k, it)["inputs"][0]
        now = _core.record_file(path)
        if now[2] != recorded["sha256"]:
            raise InputError("%s changed since the batch read it (SHA-256 %s, recorded %s): fit it again as a batch"
                             % (os.fsdecode(path), now[2], recorded["sha256"]))
        selection = (it.curve, it.curve + 1) if it.curve >= 0 else None
        again = _core.fit_files([path], s, options, csv, 1, selection, _ALL_SAMPLES)
        if len(again) != 1 or not again[0].ok:
            raise InputError("%s: read again, it %s" % (it.source, again[0].error if again else "holds no curve"))
        return FitResult(again[0].summary, options.branch, record(k, it))

    return _batch(items, options.branch, record, refit)


def _report_dir(report: Optional[Union[str, "os.PathLike[str]"]]) -> Optional[str]:
    """The report's directory, created and checked before any fitting (None: no report)."""
    if report is None:
        return None
    directory = _path("report", report)
    _core.prepare_report_dir(directory, "report")
    return directory


def _write_report(items: Sequence[Any], options: Any, directory: str, subtitle: str) -> None:
    """Writes the report's page atomically: a private temporary file renamed over index.html,
    which keeps the mode and owner of a page it replaces (as the CLI's outputs do)."""
    html = _core.map_report_html(items, options, "layerjkr force-map report", subtitle)
    target = os.path.join(directory, "index.html")
    fd, tmp = tempfile.mkstemp(prefix=".index.html.", dir=directory)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(html)
            f.flush()
            os.fsync(f.fileno())
        try:
            old = os.stat(target)
            if (old.st_uid, old.st_gid) != (os.getuid(), os.getgid()):
                os.chown(tmp, old.st_uid, old.st_gid)
            os.chmod(tmp, old.st_mode & 0o7777)
        except FileNotFoundError:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


_with_fit_parameters(fit_files)
