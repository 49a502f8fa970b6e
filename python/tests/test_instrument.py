"""Instrument files through the binding (needs ../shared/data/instrument: skipped without it)."""
import json

import numpy as np
import pytest

import layerjkr


def test_read_instrument_matches_the_reference(instrument_dir, source):
    reference = json.loads((instrument_dir / "reference.json").read_text())
    curves = layerjkr.read_instrument(instrument_dir / "fmt-jpk-fd_map2x2_extracted.jpk-force-map")
    assert len(curves) == 4
    assert curves[0]["delta"].dtype == np.float64 and curves[0]["segment"].shape == curves[0]["P"].shape
    assert all(c["spring_constant"] > 0 for c in curves)
    assert reference  # the C++ suite checks every value; here: the binding reads the same file
    with pytest.raises(layerjkr.InputError):
        layerjkr.read_instrument(source / "README.md")


def test_fit_files_on_an_archive_equals_the_cli_map(instrument_dir, source, cli, tmp_path):
    import subprocess
    archive = instrument_dir / "fmt-jpk-fd_spot3-0192.jpk-force"
    scene = str(source / "data/scenes/hydrogel_film_two_term.json")
    items = layerjkr.fit_files([archive], scene, free=["E", "delta0", "P0"], jobs=1)
    assert len(items) == 1
    out = tmp_path / "map.csv"
    r = subprocess.run([cli, "fit-map", str(archive), "--scene", scene, "--free", "E,delta0,P0", "--jobs", "1", "--out",
                        str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    header, row = out.read_text().splitlines()[:2]
    cells = dict(zip(header.split(","), row.split(",")))
    assert items[0].ok == (cells["status"] == "ok")
    assert items[0].curve == (int(cells["curve"]) if cells["curve"] else None)
    if items[0].ok:
        assert items[0].result.values["E"] == float(cells["E"])
        assert items[0].result.errors["E"] == float(cells["E_stderr"])
