"""A batch's results as tables and images: BatchResults (the list fit_batch and fit_files return)
with to_pandas (the fit-map CSV's columns), image and to_xarray (each field on the map grid,
coordinates in metres) and to_tiff (fit-map --tiff's writer). pandas and xarray are imported
only when their method is called."""
from __future__ import annotations

import html
import math
import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _core
from ._core import InputError
from ._html import number, table

_HEAD = ("file", "curve", "x", "y", "grid_x", "grid_y", "status", "error", "model", "converged", "iterations",
         "rms_residual", "identifiable", "identifiability", "contact_point", "contact_point_err", "range_samples")


_UNITS = {"rms_residual": "N", "pull_off": "N", "iterations": "", "contact_point": "m"}


def _unit(field: str) -> str:
    """The SI unit of a field: its parameter's (errors share it), or the fixed ones."""
    base = field[:-7] if field.endswith("_stderr") else field
    return _UNITS[base] if base in _UNITS else _core.unit_of(base)


_LONG_NAMES = {"E": "Young's modulus", "w": "work of adhesion", "delta0": "contact point", "P0": "force baseline",
               "K": "foundation modulus", "G": "foundation shear stiffness", "R": "indenter radius",
               "sigma0": "Dugdale stress", "E_inf": "relaxed modulus", "tau": "relaxation time",
               "beta": "relaxation exponent", "E_2": "second arm's modulus", "tau_2": "second arm's relaxation time",
               "v_star": "crack speed scale", "n": "crack kinetics exponent", "drag": "lever drag coefficient",
               "rms_residual": "rms force residual", "pull_off": "measured pull-off force"}


def _long_name(field: str) -> str:
    """What a field is, for xarray's long_name (plot labels): the standard error of a parameter too."""
    if field.endswith("_stderr"):
        return "standard error of the " + _long_name(field[:-7])
    return _LONG_NAMES.get(field, field)


def _import(module: str, method: str, package: str) -> Any:
    try:
        return __import__(module)
    except ImportError:
        raise ImportError("BatchResults.%s needs %s (Debian: %s; pip: %s)" % (method, module, package, module)) from None


class BatchResults(list):  # type: ignore[type-arg]
    """The results of :func:`fit_batch` and :func:`fit_files`: a list of :class:`BatchResult`,
    one per curve in input order, that also becomes a table (:meth:`to_pandas`), an image of a
    field (:meth:`image`), a labelled dataset of every field (:meth:`to_xarray`) and a TIFF
    (:meth:`to_tiff`). Failed curves are rows with ``status`` "error" and NaN pixels."""

    def __init__(self, items: Sequence[Any] = (), quality: Sequence[str] = (), refit: Any = None) -> None:
        super().__init__(items)
        self.quality: List[str] = list(quality) if quality else ["" for _ in self]
        """Per curve: fit-map's quality column (ok, warning, not identifiable, not converged, failed)."""
        self._refit = refit

    def __getstate__(self) -> Dict[str, Any]:
        # Pickled (Dask ships batches between processes) without the way back to its inputs: the
        # caller's arrays and a scene stay where they were.
        state = dict(self.__dict__)
        state["_refit"] = None
        return state

    def fit_curve(self, k: int) -> Any:
        """Curve ``k`` fitted again alone, with its samples: the arrays ``fit_batch`` was given,
        or the curve read again from its file by ``fit_files`` (refused if the file's SHA-256
        changed). The same scene and options give the same values as ``self[k].result``; the
        FitResult also holds delta, P, P_fit and the residuals, for :meth:`plot`.

        Raises
        ------
        InputError
            Curve ``k`` failed in the batch (its error quoted), its file changed or is gone, or
            these results were not made by ``fit_batch``/``fit_files`` (an interrupted batch).
        """
        item = self[k]
        if item.result is None:
            raise InputError("results[%d] (%s) was not fitted: %s" % (k, item.source, item.error))
        if self._refit is None:
            raise InputError("results[%d]: these results do not know their inputs (an interrupted or unpickled "
                             "batch's); fit the curve alone" % k)
        return self._refit(k % len(self))

    def plot(self, k: int, ax: Any = None) -> Any:
        """Data, fit and residuals of curve ``k`` (:meth:`fit_curve`, then ``FitResult.plot``)."""
        return self.fit_curve(k).plot(ax)

    def __repr__(self) -> str:
        # A summary of the batch, not every item in full (items print one by one: results[i]).
        ok = sum(1 for it in self if it.result is not None)
        quality: Dict[str, int] = {}
        for q in self.quality:
            quality[q or "unknown"] = quality.get(q or "unknown", 0) + 1
        said = ", ".join("%s %d" % (q, n) for q, n in sorted(quality.items()))
        files = len({it.source.split("#")[0] for it in self})
        return "BatchResults(%d curves from %d input(s): %d fitted, %d failed; fields %s; quality: %s)" % (
            len(self), files, ok, len(self) - ok, ", ".join(self._free()) or "-", said or "-")

    def _repr_html_(self) -> str:
        # Counts and quality, then each fitted field's median and spread over the fitted curves.
        ok = [it.result for it in self if it.result is not None]
        quality: Dict[str, int] = {}
        for q in self.quality:
            quality[q or "unknown"] = quality.get(q or "unknown", 0) + 1
        rows = []
        for name in self._free():
            v = np.array([r.values[name] for r in ok if name in r.parameters], dtype=float)
            v = v[np.isfinite(v)]
            rows.append((html.escape(name), len(v), number(float(np.median(v))) if len(v) else "-",
                         number(float(np.percentile(v, 25))) if len(v) else "-",
                         number(float(np.percentile(v, 75))) if len(v) else "-",
                         html.escape(_core.unit_of(name.split("[")[0]))))
        failures = ["%s: %s" % (it.source, it.error) for it in self if it.result is None][:5]
        return table("layerjkr batch: %d curves, %d fitted, %d failed; quality: %s" % (
            len(self), len(ok), len(self) - len(ok), ", ".join("%s %d" % kv for kv in sorted(quality.items())) or "-"),
            ("field", "fitted", "median", "25 %", "75 %", "unit"), rows, failures)

    def _free(self) -> List[str]:
        for it in self:
            if it.result is not None:
                return list(it.result.parameters)
        return []

    def fields(self) -> List[str]:
        """The numeric fields an image can show: each free parameter and its ``_stderr``,
        ``rms_residual``, ``pull_off``, ``iterations`` and ``contact_point``."""
        names = []
        for p in self._free():
            names += [p, p + "_stderr"]
        return names + ["rms_residual", "pull_off", "iterations", "contact_point"]

    def _value(self, it: Any, field: str) -> float:
        r = it.result
        if r is None:
            return math.nan
        if field in r.parameters:
            return float(r.values[field])
        if field.endswith("_stderr") and field[:-7] in r.parameters:
            return float(r.errors[field[:-7]])
        if field == "rms_residual":
            return float(r.rms_residual)
        if field == "pull_off":
            return float(r._fields["pull_off_force"])
        if field == "iterations":
            return float(r.iterations)
        if field == "contact_point":
            return float(r.contact_point.get("value", math.nan))
        raise InputError("field = %r is not a field of these results (fields: %s)" % (field, ", ".join(self.fields())))

    def to_pandas(self) -> Any:
        """A pandas DataFrame with the columns of ``layerjkr fit-map``'s CSV, one row per curve."""
        pd = _import("pandas", "to_pandas", "python3-pandas")
        free = self._free()
        rows = []
        for it, quality in zip(self, self.quality):
            r = it.result
            row: Dict[str, Any] = {"file": it.source, "curve": it.curve, "x": it.x, "y": it.y, "grid_x": it.grid_x,
                                   "grid_y": it.grid_y, "status": "ok" if r is not None else "error",
                                   "error": it.error or ""}
            if r is not None:
                point = r.contact_point
                row.update(model=r.model, converged=r.converged, iterations=r.iterations, rms_residual=r.rms_residual,
                           identifiable=r.identifiable, identifiability=r._fields.get("identifiability", ""),
                           contact_point=point.get("value"), contact_point_err=point.get("stderr"),
                           range_samples=point.get("samples_in_range"))
            for p in free:
                row[p] = self._value(it, p)
                row[p + "_stderr"] = self._value(it, p + "_stderr")
            row.update(quality=quality, warnings=" | ".join(r.warnings) if r is not None else "",
                       notices=" | ".join(r.notices) if r is not None else "")
            rows.append(row)
        columns = list(_HEAD) + [c for p in free for c in (p, p + "_stderr")] + ["quality", "warnings", "notices"]
        return pd.DataFrame(rows, columns=columns)

    def _of_file(self, file: Optional[str], method: str) -> List[Any]:
        """The curves of one map: those of ``file``, or of the only file whose curves have pixels."""
        def stem(it: Any) -> str:  # the file: a map's curve is "FILE#N", N its curve number
            suffix = "#%d" % it.curve if it.curve is not None else None
            return it.source[:-len(suffix)] if suffix and it.source.endswith(suffix) else it.source
        mapped = [it for it in self if it.grid_x is not None and it.grid_y is not None]
        files = list(dict.fromkeys(stem(it) for it in mapped))
        if file is None:
            if len(files) != 1:
                raise InputError("%s: %s; give file=" % (method, "no curve has a map pixel (instrument maps have them)"
                                                             if not files else "the results hold %d maps (%s)" %
                                                             (len(files), ", ".join(files))))
            file = files[0]
        chosen = [it for it in mapped if stem(it) == os.fsdecode(file)]
        if not chosen:
            raise InputError("%s: file = %r has no curve with a map pixel here (maps: %s)" % (method, file, ", ".join(files)))
        return chosen

    def image(self, field: str, *, file: Optional[str] = None) -> npt.NDArray[np.float64]:
        """A field on the map grid: a float64 array [grid_y, grid_x], NaN where a curve failed or
        the grid has none. ``file`` picks the map when the results hold several."""
        return self._image(self._of_file(file, "image"), field)

    def _image(self, items: Sequence[Any], field: str) -> npt.NDArray[np.float64]:
        values = [self._value(it, field) for it in items]
        return _core.map_image([it.grid_x for it in items], [it.grid_y for it in items], values)

    def to_xarray(self, *, file: Optional[str] = None) -> Any:
        """An xarray Dataset of every field on the map grid: dims (y, x), coordinates ``x`` and
        ``y`` in metres (each column's and row's mean stage position; NaN where a whole column
        or row failed to read), ``grid_x`` and ``grid_y``; each variable's ``units`` and
        ``long_name`` in its attrs; ``quality`` (fit-map's column, "" where no curve) per pixel; the
        first fit's provenance record as JSON in the Dataset's attrs."""
        import json
        xr = _import("xarray", "to_xarray", "python3-xarray")
        items = self._of_file(file, "to_xarray")
        gx = np.array([it.grid_x for it in items])
        gy = np.array([it.grid_y for it in items])
        data = {}
        for field in self.fields():
            data[field] = (("y", "x"), self._image(items, field), {"units": _unit(field), "long_name": _long_name(field)})
        shape = data[self.fields()[0]][1].shape
        # The quality strings placed as the values are (one placement rule): codes through map_image.
        where = {id(it): k for k, it in enumerate(self)}
        labels = sorted(set(self.quality))
        codes = _core.map_image(list(gx), list(gy), [float(labels.index(self.quality[where[id(it)]])) for it in items])
        quality = np.array([[labels[int(c)] if np.isfinite(c) else "" for c in row] for row in codes], dtype=object)
        data["quality"] = (("y", "x"), quality, {"long_name": "fit-map's quality (ok, warning, not identifiable, "
                                                              "not converged, failed)"})
        first = next((it.result for it in items if it.result is not None), None)
        provenance = json.dumps(first.provenance) if first is not None and first.provenance else ""

        def axis(positions: npt.NDArray[np.float64], index: npt.NDArray[np.int64], n: int) -> npt.NDArray[np.float64]:
            out = np.full(n, np.nan)
            for k in range(n):
                mine = positions[(index == k) & np.isfinite(positions)]
                if mine.size:
                    out[k] = float(mine.mean())
            return out

        xs = axis(np.array([it.x for it in items], float), gx, shape[1])
        ys = axis(np.array([it.y for it in items], float), gy, shape[0])
        return xr.Dataset(data, coords={"x": ("x", xs, {"units": "m"}), "y": ("y", ys, {"units": "m"}),
                                        "grid_x": ("x", np.arange(shape[1])), "grid_y": ("y", np.arange(shape[0]))},
                          attrs={"source": "layerjkr %s" % _core.__version__, "provenance": provenance})

    def to_tiff(self, field: str, path: Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"], *,
                file: Optional[str] = None) -> None:
        """Writes :meth:`image` of ``field`` to ``path`` as a 32-bit float TIFF (ImageJ, Fiji,
        Gwyddion; NaN where no fit) with the writer of ``fit-map --tiff``; replaces ``path``."""
        image = self.image(field, file=file)  # checks the field first
        unit = _unit(field)
        # Bytes reach the file system as given: a name that is not UTF-8 (os.fsdecode's surrogates)
        # is written, not refused by the binding's text conversion.
        _core.write_tiff(os.fsencode(path), image,
                         "layerjkr fit-map: %s%s" % (field, " [%s]" % unit if unit else ""))
