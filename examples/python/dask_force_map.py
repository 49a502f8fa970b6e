#!/usr/bin/python3
"""What this teaches: fitting a force map - one big map file, several maps or a directory of
curves - on a Dask cluster (your laptop's cores with a LocalCluster, or many machines through a
scheduler address), and gathering the results into the table `layerjkr fit-map` writes, row for
row and digit for digit, plus a map image.

How the work is split: into tasks of about --chunk curves (default 256). A map holding more
curves than that is cut into curve ranges: layerjkr.open_instrument(path) reads only its header
and index to count them, and each task calls layerjkr.fit_files([path], curves=(a, b), jobs=1),
which reads and fits only the curves a .. b - 1 - so one QI map of 65 536 curves spreads over
every worker. Smaller files (single curves, CSV files, small maps) are grouped whole, about
--chunk curves per task. Each task runs on one thread of a worker (the C++ fit releases the
GIL); the gathered tasks, in order, are the curves in file order.

Run (a local cluster of 2 workers, one thread each):
    PYTHONPATH=build/python examples/python/dask_force_map.py MAP.jpk-qi-data --scene S.json \
        --free E,delta0,P0 --out results.csv --plot map_E.png
On a cluster: start `dask scheduler` and `dask worker tcp://HOST:8786` on each machine (each
with layerjkr installed and the files at the same path), then pass --scheduler tcp://HOST:8786.
On SLURM, dask-jobqueue's SLURMCluster starts the workers as jobs: see docs/python.md.
"""
import argparse
import glob
import math
import os
import re
import sys

import layerjkr

INSTRUMENT = (".jpk-force", ".jpk-force-map", ".jpk-qi-data", ".ibw", ".spm")
NANOSCOPE_NUMBERED = re.compile(r"\.[0-9]{3}$")  # Bruker's .000 - .999
# layerjkr.fit_files' keywords this script passes on: name -> type.
OPTIONS = {"branch": str, "control": str, "spring_constant": float, "baseline": str, "window": str,
           "window_fraction": float, "loss": str, "loss_scale": float, "starts": int, "max_iterations": int,
           "units": str}


def is_instrument(path):
    return path.endswith(INSTRUMENT) or bool(NANOSCOPE_NUMBERED.search(path))


def expand(inputs):
    """Directories (their *.csv and instrument files), glob patterns and files, sorted per input
    (as `layerjkr fit-map` expands them)."""
    files = []
    for item in inputs:
        if os.path.isdir(item):
            files += sorted(os.path.join(item, f) for f in os.listdir(item)
                            if f.endswith(".csv") or is_instrument(f))
        elif any(c in item for c in "*?["):
            files += sorted(glob.glob(item))
        else:
            files.append(item)
    return files


def curve_count(path):
    """How many curves a file holds: its index for an instrument file (no samples are read), 1
    for a CSV file. A file that cannot be opened counts 1: fit_files gives it its failed row."""
    if not is_instrument(path):
        return 1
    try:
        with layerjkr.open_instrument(path) as f:
            return len(f)
    except layerjkr.Error:
        return 1


def plan(files, chunk):
    """The tasks, in file order: (paths, None) fits those files whole; ([path], (a, b)) fits the
    curves a .. b - 1 of one map that holds more than `chunk` curves."""
    tasks, group, count = [], [], 0
    for path in files:
        n = curve_count(path)
        if group and (n > chunk or count + n > chunk):
            tasks.append((group, None))
            group, count = [], 0
        if n > chunk:
            tasks += [([path], (a, min(a + chunk, n))) for a in range(0, n, chunk)]
        else:
            group.append(path)
            count += n
    if group:
        tasks.append((group, None))
    return tasks


def fit_task(task, scene, free, options):
    """One task: whole files or one map's curve range; layerjkr.BatchResult items (picklable)."""
    paths, curves = task
    return layerjkr.fit_files(paths, scene, free=free, jobs=1, curves=curves, **options)


def csv_cell(text):
    """A cell as fit-map quotes it: in quotes if it holds a comma, quote or line break (quotes
    doubled, line breaks as spaces); Python's csv module would differ on the line breaks."""
    if not any(c in text for c in ',"\n\r'):
        return text
    return '"' + text.replace('"', '""').replace("\n", " ").replace("\r", " ") + '"'


def shortest(v):
    """repr's shortest round-trip digits, as C's format_double writes them (1000, not 1000.0)."""
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def rows_for(items, free):
    """The header and rows of `layerjkr fit-map`, as its text: numbers in their shortest round-trip
    form, whole numbers without '.0' (fit-map's format_double), non-finite and absent values empty."""
    header = ["file", "curve", "x", "y", "grid_x", "grid_y", "status", "error", "model", "converged", "iterations",
              "rms_residual", "identifiable", "identifiability", "contact_point", "contact_point_err",
              "range_samples"]
    for p in free:
        header += [p, p + "_stderr"]
    header += ["quality", "warnings", "notices"]
    rows = []
    num = lambda v: "" if v is None or not math.isfinite(v) else shortest(v)
    index = lambda v: "" if v is None else str(v)
    for it in items:
        row = [csv_cell(it.source), index(it.curve), num(it.x), num(it.y), index(it.grid_x), index(it.grid_y),
               "ok" if it.ok else "error", csv_cell(it.error or "")]
        if it.ok:
            r = it.result
            row += [r.model, str(int(r.converged)), str(r.iterations), shortest(r.rms_residual),
                    str(int(r.identifiable)),
                    csv_cell("yes" if r.identifiable else
                             ("no: " if r.identifiability_known else "unknown: ") + r.identifiability_reason)]
            c = r.contact_point
            row += [num(c["value"]), num(c["stderr"]), str(c["samples_in_range"])]
            for p in free:
                row += [num(r.values[p]), num(r.errors[p])]
            quality = ("not converged" if not r.converged else "not identifiable" if not r.identifiable else
                       "warning" if r.warnings else "ok")
            row += [quality, csv_cell(" | ".join(r.warnings)), csv_cell(" | ".join(r.notices))]
        else:
            row += [""] * (9 + 2 * len(free)) + ["failed", "", ""]
        rows.append(row)
    return header, rows


def plot_map(items, parameter, path):
    """The fitted parameter over the map grid (or, for loose files, in file order on a square)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    on_grid = all(it.grid_x is not None for it in items)
    side = max(1, math.ceil(math.sqrt(len(items))))
    nx = max(it.grid_x for it in items) + 1 if on_grid else side
    ny = max(it.grid_y for it in items) + 1 if on_grid else math.ceil(len(items) / side)
    image = np.full((ny, nx), np.nan)
    for k, it in enumerate(items):
        gx, gy = (it.grid_x, it.grid_y) if on_grid else (k % side, k // side)
        if it.ok:
            image[gy, gx] = it.result.values[parameter]
    fig, ax = plt.subplots(figsize=(5, 4))
    shown = ax.imshow(image, origin="lower", cmap="viridis")
    fig.colorbar(shown, ax=ax, label=parameter + " (SI)")
    ax.set_title("%s over the map (%d curves)" % (parameter, len(items)))
    ax.set_xlabel("grid x" if on_grid else "file (row-major)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(files, scene, free, options, client, chunk):
    futures = client.map(fit_task, plan(files, chunk), scene=scene, free=free, options=options, pure=False)
    return [item for part in client.gather(futures) for item in part]


def main(argv=None, client=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("inputs", nargs="+")
    ap.add_argument("--scene", required=True, help="scene JSON (the CLI's schema)")
    ap.add_argument("--free", required=True, help="comma-separated parameters, e.g. E,w,delta0")
    ap.add_argument("--out", required=True, help="results CSV (the columns of layerjkr fit-map)")
    ap.add_argument("--plot", help="PNG of the first free parameter over the map")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster workers, one thread each (default 2)")
    ap.add_argument("--chunk", "--partition-size", dest="chunk", type=int, default=256,
                    help="curves per task (default 256): a bigger map is cut into ranges of this many")
    for name, kind in OPTIONS.items():
        ap.add_argument("--" + name.replace("_", "-"), dest=name, type=kind,
                        help="layerjkr.fit_files(%s=...) (default: its default)" % name)
    a = ap.parse_args(argv)
    if a.chunk < 1:
        ap.error("--chunk must be >= 1")
    free = a.free.split(",")
    options = {k: getattr(a, k) for k in OPTIONS if getattr(a, k) is not None}
    files = expand(a.inputs)
    if not files:
        ap.error("no curve files in " + " ".join(a.inputs))
    layerjkr.scene(a.scene)  # a bad scene fails here, once, not in every task
    own = None
    if client is None:
        from dask.distributed import Client, LocalCluster
        if a.scheduler:
            client = own = Client(a.scheduler)
        else:
            own = LocalCluster(n_workers=a.workers, threads_per_worker=1, dashboard_address=None)
            client = Client(own)
    try:
        items = run(files, os.path.abspath(a.scene), free, options, client, a.chunk)
    finally:
        if own is not None:
            client.close()
            own.close()
    header, rows = rows_for(items, free)
    with open(a.out, "w", newline="") as f:
        for row in [header] + rows:
            f.write(",".join(row) + "\n")
    if a.plot:
        plot_map(items, free[0], a.plot)
    failed = sum(not it.ok for it in items)
    print("fitted %d curves from %d files, %d failed; wrote %s" % (len(items), len(files), failed, a.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
