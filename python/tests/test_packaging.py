"""pip install . of the package (pyproject.toml + setup.py), on a copy of the source tree so
that nothing is written into the real one, reusing the configured build directory
(LAYERJKR_CMAKE_BUILD_DIR) so the test does not rebuild the library."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest


def test_pip_install_builds_an_importable_package(source, tmp_path):
    build_dir = pathlib.Path(os.environ.get("LAYERJKR_BUILD_DIR", source / "build"))
    if not (build_dir / "CMakeCache.txt").exists():
        pytest.skip("no configured build directory at %s" % build_dir)
    tree = tmp_path / "src"
    shutil.copytree(source, tree, ignore=shutil.ignore_patterns(".git", "build", "build-*", "*.egg-info", "__pycache__"))
    target = tmp_path / "site"
    env = dict(os.environ, LAYERJKR_CMAKE_BUILD_DIR=str(build_dir))
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index",
                        "--target", str(target), str(tree)], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    check = ("import layerjkr; print(layerjkr.__file__); "
             "print(layerjkr.summary(%r)['pull_off_force'])" % str(source / "data/scenes/hydrogel_film_two_term.json"))
    env = dict(os.environ, PYTHONPATH=str(target))
    r = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    path, force = r.stdout.split()
    assert path.startswith(str(target))
    assert float(force) < 0
