"""examples/notebooks/afm_map.ipynb runs top to bottom in a fresh kernel (nbclient), so the
notebook never rots; its cells assert what they show (the JKR fit within its error bars)."""
import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("LAYERJKR_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def test_the_notebook_runs(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    path = SOURCE / "examples" / "notebooks" / "afm_map.ipynb"
    nb = nbformat.read(str(path), as_version=4)
    env_dir = tmp_path / "run"
    env_dir.mkdir()
    # The kernel is a new process in another directory: it finds this layerjkr by absolute path.
    import layerjkr
    package_root = str(pathlib.Path(layerjkr.__file__).resolve().parents[1])
    os.environ["PYTHONPATH"] = os.pathsep.join([package_root] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    os.environ.setdefault("MPLBACKEND", "Agg")
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger note on frozen modules
    client = nbclient.NotebookClient(nb, timeout=240, kernel_name="python3", resources={"metadata": {"path": str(env_dir)}})
    client.execute()
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    text = "".join(o.get("text", "") for o in outputs)
    assert "pull-off of the fitted scene" in text
    html = [o["data"]["text/html"] for o in outputs if "data" in o and "text/html" in o["data"]]
    assert any("layerjkr fit" in h for h in html)  # the FitResult's table
