"""examples/python/dask_force_map.py on a LocalCluster of 2 workers against the serial
`layerjkr fit-map` on a small generated map: the same rows, the same numbers."""
import csv
import importlib.util
import subprocess

import pytest

distributed = pytest.importorskip("distributed")


def load_example(source):
    spec = importlib.util.spec_from_file_location("dask_force_map", source / "examples/python/dask_force_map.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def generated_map(source, directory, n):
    """n curves: the bundled sample with its force scaled by 1 + 2 % k (so E differs per curve)."""
    lines = (source / "data/curves/hydrogel_film_two_term.csv").read_text().splitlines()
    body = [line for line in lines if not line.startswith("#")]
    directory.mkdir()
    for k in range(n):
        rows = [body[0]]
        for line in body[1:]:
            d, p, s = line.split(",")
            rows.append("%s,%r,%s" % (d, float(p) * (1 + 0.02 * k), s))
        (directory / ("curve_%02d.csv" % k)).write_text("\n".join(rows) + "\n")


def read_rows(path):
    with open(path, newline="") as f:
        return {row["file"].rsplit("/", 1)[-1]: row for row in csv.DictReader(f)}


def test_dask_map_equals_serial_fit_map(source, cli, tmp_path):
    generated_map(source, tmp_path / "map", 8)
    scene = str(source / "data/scenes/hydrogel_film_two_term.json")
    serial = tmp_path / "serial.csv"
    r = subprocess.run([cli, "fit-map", str(tmp_path / "map"), "--scene", scene, "--free", "E,w,delta0,P0", "--branch",
                        "all", "--jobs", "1", "--out", str(serial)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    example = load_example(source)
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None,
                                       local_directory=str(tmp_path / "dask"))
    client = distributed.Client(cluster)
    try:
        assert len(client.scheduler_info()["workers"]) == 2
        out = tmp_path / "dask.csv"
        example.main([str(tmp_path / "map"), "--scene", scene, "--free", "E,w,delta0,P0", "--branch", "all", "--out",
                      str(out), "--partition-size", "3", "--plot", str(tmp_path / "map_E.png")], client=client)
    finally:
        client.close()
        cluster.close()
    a, b = read_rows(serial), read_rows(out)
    assert sorted(a) == sorted(b) and len(a) == 8
    for name in a:
        assert a[name]["status"] == b[name]["status"] == "ok"
        for column in ["E", "E_stderr", "w", "w_stderr", "delta0", "P0", "rms_residual", "iterations"]:
            assert float(a[name][column]) == float(b[name][column]), (name, column)
    assert (tmp_path / "map_E.png").stat().st_size > 1000
