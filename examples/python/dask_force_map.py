#!/usr/bin/python3
"""What this teaches: fitting a whole force map (or a directory of curves) on a Dask cluster -
your laptop's cores with a LocalCluster, or many machines through a scheduler address - and
gathering the results into the table `layerjkr fit-map` writes, plus a map image.

How the work is split: the files are cut into partitions of --partition-size; each task fits
one partition with layerjkr.fit_files(jobs=1) on one thread of a worker (the C++ fit releases
the GIL). A map archive (.jpk-force-map, .jpk-qi-data) is one file, so one task: give a
directory of single curves or several maps to spread the work.

Run (a local cluster of 2 workers, one thread each):
    PYTHONPATH=build/python examples/python/dask_force_map.py DIR --scene S.json --free E,w,delta0 \
        --out results.csv --plot map_E.png
On a cluster: start `dask scheduler` and `dask worker tcp://HOST:8786` on each machine (each
with layerjkr installed), then pass --scheduler tcp://HOST:8786. On SLURM, dask-jobqueue's
SLURMCluster starts the workers as jobs: see README ("Force maps on Dask").
"""
import argparse
import csv
import glob
import math
import os
import sys

import layerjkr

INSTRUMENT = (".jpk-force", ".jpk-force-map", ".jpk-qi-data", ".ibw")
# layerjkr.fit_files' keywords this script passes on: name -> type.
OPTIONS = {"branch": str, "control": str, "spring_constant": float, "baseline": str, "window": str,
           "window_fraction": float, "loss": str, "loss_scale": float, "starts": int, "max_iterations": int,
           "units": str}


def expand(inputs):
    """Directories (their *.csv and instrument files), glob patterns and files, sorted per input."""
    files = []
    for item in inputs:
        if os.path.isdir(item):
            files += sorted(os.path.join(item, f) for f in os.listdir(item)
                            if f.endswith(".csv") or f.endswith(INSTRUMENT))
        elif any(c in item for c in "*?["):
            files += sorted(glob.glob(item))
        else:
            files.append(item)
    return files


def fit_partition(paths, scene, free, options):
    """One task: fit a partition of files; layerjkr.BatchResult items (picklable) for the gather."""
    return layerjkr.fit_files(paths, scene, free=free, jobs=1, **options)


def rows_for(items, free):
    """The columns of `layerjkr fit-map`, in its order."""
    header = ["file", "curve", "x", "y", "grid_x", "grid_y", "status", "error", "model", "converged", "iterations",
              "rms_residual", "identifiable"]
    for p in free:
        header += [p, p + "_stderr"]
    rows = []
    num = lambda v: "" if v is None or (isinstance(v, float) and not math.isfinite(v)) else repr(float(v))
    index = lambda v: "" if v is None else str(v)
    for it in items:
        row = [it.source, index(it.curve), num(it.x), num(it.y), index(it.grid_x), index(it.grid_y),
               "ok" if it.ok else "error", it.error or ""]
        if it.ok:
            r = it.result
            row += [r.model, int(r.converged), r.iterations, repr(r.rms_residual), int(r.identifiable)]
            for p in free:
                row += [num(r.values[p]), num(r.errors[p])]
        else:
            row += [""] * (5 + 2 * len(free))
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


def run(files, scene, free, options, client, partition_size):
    partitions = [files[i:i + partition_size] for i in range(0, len(files), partition_size)]
    futures = client.map(fit_partition, partitions, scene=scene, free=free, options=options, pure=False)
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
    ap.add_argument("--partition-size", type=int, default=16, help="files per task (default 16)")
    for name, kind in OPTIONS.items():
        ap.add_argument("--" + name.replace("_", "-"), dest=name, type=kind,
                        help="layerjkr.fit_files(%s=...) (default: its default)" % name)
    a = ap.parse_args(argv)
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
        items = run(files, os.path.abspath(a.scene), free, options, client, a.partition_size)
    finally:
        if own is not None:
            client.close()
            own.close()
    header, rows = rows_for(items, free)
    with open(a.out, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    if a.plot:
        plot_map(items, free[0], a.plot)
    failed = sum(not it.ok for it in items)
    print("fitted %d curves from %d files, %d failed; wrote %s" % (len(items), len(files), failed, a.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
