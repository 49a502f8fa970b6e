#!/usr/bin/python3
"""The Python layer's cost, measured against the C++ it wraps; prints a table (docs/python.md).

1. Binding overhead of layerjkr.curve(scene, 200 radii): per call, the wall time seen from
   Python minus the time the C++ answer took inside that same call (Curve.seconds, the
   library's CurveAnswer::seconds), median over 600 calls; beside it the C++ call alone
   (bench_models BM_CurveTable200_Hydrogel).
2. A fit of the bundled sample from Python against bench_fit BM_FitBundledSample.
3. A 512-curve map (partitions of 32) on a LocalCluster of 2 single-thread workers (examples/python/
   dask_force_map.py, cluster already started) against `layerjkr fit-map --jobs 2`.

Run: PYTHONPATH=build/python python/bench/bench_python.py [BUILD_DIR]   (about a minute)
"""
import importlib.util
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import layerjkr

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build")
SCENE = str(ROOT / "data/scenes/hydrogel_film_two_term.json")
N_CURVES, PARTITION = 512, 32


def cpp_median(binary, name, repetitions):
    out = subprocess.run([str(BUILD / "bin" / binary), "--benchmark_filter=^%s$" % name, "--benchmark_format=json",
                          "--benchmark_repetitions=%d" % repetitions], capture_output=True, text=True, check=True)
    runs = [b for b in json.loads(out.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    scale = {"us": 1e-6, "ms": 1e-3, "ns": 1e-9}[runs[0]["time_unit"]]
    return statistics.median(b["real_time"] for b in runs) * scale


def py_median(call, batches, per_batch):
    call()
    times = []
    for _ in range(batches):
        t = time.perf_counter()
        for _ in range(per_batch):
            call()
        times.append((time.perf_counter() - t) / per_batch)
    return statistics.median(times)


def sample():
    body = [line for line in (ROOT / "data/curves/hydrogel_film_two_term.csv").read_text().splitlines()
            if not line.startswith("#")]
    data = np.array([[float(v) for v in line.split(",")] for line in body[1:]])
    return body, data


def main():
    rows = []
    scene = layerjkr.scene(SCENE)
    a = np.linspace(1e-7, 2e-6, 200)
    overheads, totals = [], []
    for _ in range(600):
        t = time.perf_counter()
        inner = layerjkr.curve(scene, a).seconds
        total = time.perf_counter() - t
        overheads.append(total - inner)
        totals.append(total)
    cpp = cpp_median("bench_models", "BM_CurveTable200_Hydrogel", 30)
    rows.append(("curve, 200 radii", cpp, statistics.median(totals),
                 "binding overhead %.1f us" % (statistics.median(overheads) * 1e6)))

    body, data = sample()
    fit = lambda: layerjkr.fit(data[:, 0], data[:, 1], scene, free=["E", "w", "delta0", "P0"],
                               segment=data[:, 2], branch="all")
    py = py_median(fit, 15, 20)
    cpp = cpp_median("bench_fit", "BM_FitBundledSample", 15)
    rows.append(("fit of the bundled sample", cpp, py, "ratio %.3f" % (py / cpp)))

    spec = importlib.util.spec_from_file_location("dask_force_map", ROOT / "examples/python/dask_force_map.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    from dask.distributed import Client, LocalCluster
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        files = []
        for k in range(N_CURVES):
            lines = [body[0]] + ["%s,%r,%s" % (d, float(p) * (1 + 0.005 * k), s) for d, p, s in
                                 (line.split(",") for line in body[1:])]
            f = tmp / ("curve_%02d.csv" % k)
            f.write_text("\n".join(lines) + "\n")
            files.append(str(f))
        args = ["--scene", SCENE, "--free", "E,w,delta0,P0", "--branch", "all"]
        cli_times = []
        for _ in range(5):
            t = time.perf_counter()
            subprocess.run([str(BUILD / "bin" / "layerjkr"), "fit-map", str(tmp), *args, "--jobs", "2", "--out",
                            str(tmp / "cli.csv")], capture_output=True, check=True)
            cli_times.append(time.perf_counter() - t)
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, local_directory=str(tmp / "dask"))
        client = Client(cluster)
        try:
            options = {"branch": "all"}
            example.run(files, SCENE, ["E", "w", "delta0", "P0"], options, client, PARTITION)
            dask_times = []
            for _ in range(5):
                t = time.perf_counter()
                example.run(files, SCENE, ["E", "w", "delta0", "P0"], options, client, PARTITION)
                dask_times.append(time.perf_counter() - t)
        finally:
            client.close()
            cluster.close()
        cpp, py = statistics.median(cli_times), statistics.median(dask_times)
        rows.append(("%d-curve map, 2 workers, partitions of %d" % (N_CURVES, PARTITION), cpp, py, "throughput ratio %.2f" % (cpp / py)))

    print("| task | C++ median | Python median | |")
    print("|---|---|---|---|")
    for task, cpp, py, note in rows:
        print("| %s | %.4g ms | %.4g ms | %s |" % (task, cpp * 1e3, py * 1e3, note))


if __name__ == "__main__":
    main()
