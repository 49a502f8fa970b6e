"""examples/python/dask_force_map.py on a LocalCluster of 2 workers against the serial
`layerjkr fit-map`: the same table, text for text and row for row - for one map of 4 096 curves
split into curve ranges, and for a directory of single-curve CSV files grouped into tasks."""
import importlib.util
import subprocess
import time
import zipfile

import pytest

distributed = pytest.importorskip("distributed")

SIDE = 64  # 4 096 curves: about 4 s of fitting with the Hertz scene below
QI = "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data"
# A cheap scene (tests/cli/test_cli_instrument.cpp's hertz_scene): thousands of fits in seconds.
HERTZ = '{"indenter": {"shape": "paraboloid", "R": 4e-8}, "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}}'


def load_example(source):
    spec = importlib.util.spec_from_file_location("dask_force_map", source / "examples/python/dask_force_map.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None,
                                       local_directory=str(tmp_path_factory.mktemp("dask")))
    c = distributed.Client(cluster)
    assert len(c.scheduler_info()["workers"]) == 2
    yield c
    c.close()
    cluster.close()


def generated_qi_map(instrument_dir, path, side):
    """A side x side QI map: the bundled 4-curve QI file's entries index/K/... copied to index/N/...
    (K = N % 4), its top-level entries (the shared header) kept. No tool binary needed."""
    with zipfile.ZipFile(instrument_dir / QI) as z:
        data = {name: z.read(name) for name in z.namelist()}
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as out:
        for name, blob in data.items():
            if not name.startswith("index/"):
                out.writestr(name, blob)
        out.writestr("index/", b"")
        for n in range(side * side):
            prefix = "index/%d/" % (n % 4)
            for name, blob in data.items():
                if name.startswith(prefix):
                    out.writestr("index/%d/%s" % (n, name[len(prefix):]), blob)


def fit_map(cli, inputs, scene, free, out, *extra):
    t0 = time.perf_counter()
    r = subprocess.run([cli, "fit-map", *inputs, "--scene", scene, "--free", free, "--out", str(out), *extra],
                       capture_output=True, text=True)
    assert r.returncode in (0, 3), r.stderr  # 3: some curves failed (their rows say why)
    return time.perf_counter() - t0


def test_one_map_split_into_curve_ranges_equals_serial_fit_map(instrument_dir, cli, source, client, tmp_path):
    path = tmp_path / "map.jpk-qi-data"
    generated_qi_map(instrument_dir, path, SIDE)
    scene = tmp_path / "hertz.json"
    scene.write_text(HERTZ)
    example = load_example(source)
    # 4 096 curves in ranges of 300: 14 tasks, the last one short.
    assert example.plan([str(path)], 300) == [([str(path)], (a, min(a + 300, SIDE * SIDE)))
                                              for a in range(0, SIDE * SIDE, 300)]
    serial = tmp_path / "serial.csv"
    t_serial = fit_map(cli, [str(path)], str(scene), "E,delta0,P0", serial, "--jobs", "1")
    out = tmp_path / "dask.csv"
    t0 = time.perf_counter()
    example.main([str(path), "--scene", str(scene), "--free", "E,delta0,P0", "--out", str(out), "--chunk", "300",
                  "--plot", str(tmp_path / "map_E.png")], client=client)
    t_dask = time.perf_counter() - t0
    a, b = serial.read_text().splitlines(), out.read_text().splitlines()
    assert len(a) == SIDE * SIDE + 1
    assert a[0] == b[0]
    for k, (x, y) in enumerate(zip(a, b)):
        assert x == y, "row %d differs" % k
    assert len(a) == len(b)
    assert sum(",ok," in row for row in a) > SIDE * SIDE // 2  # real fits, not just error rows
    assert (tmp_path / "map_E.png").stat().st_size > 1000
    print("%d curves: fit-map --jobs 1 %.2f s, Dask (2 workers, ranges of 300) %.2f s" % (SIDE * SIDE, t_serial, t_dask))


def generated_csv_curves(source, directory, n):
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


def test_a_directory_of_curves_grouped_into_tasks_equals_serial_fit_map(source, cli, client, tmp_path):
    generated_csv_curves(source, tmp_path / "map", 8)
    scene = str(source / "data/scenes/hydrogel_film_two_term.json")
    serial = tmp_path / "serial.csv"
    fit_map(cli, [str(tmp_path / "map")], scene, "E,w,delta0,P0", serial, "--branch", "all", "--jobs", "1")
    example = load_example(source)
    files = example.expand([str(tmp_path / "map")])
    assert [paths for paths, curves in example.plan(files, 3)] == [files[0:3], files[3:6], files[6:8]]
    out = tmp_path / "dask.csv"
    example.main([str(tmp_path / "map"), "--scene", scene, "--free", "E,w,delta0,P0", "--branch", "all", "--out",
                  str(out), "--partition-size", "3", "--plot", str(tmp_path / "map_E.png")], client=client)
    a, b = serial.read_text().splitlines(), out.read_text().splitlines()
    assert a == b and len(a) == 9 and all(",ok," in row for row in a[1:])
    assert (tmp_path / "map_E.png").stat().st_size > 1000
