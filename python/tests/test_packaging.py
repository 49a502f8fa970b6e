"""pip install . of the package (pyproject.toml + setup.py), on a copy of the source tree so
that nothing is written into the real one, reusing the configured build directory
(LAYERJKR_CMAKE_BUILD_DIR) so the test does not rebuild the library."""
import os
import pathlib
import re
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
    check = ("import layerjkr; print(layerjkr.__file__); print(layerjkr.__version__); "
             "print(layerjkr.summary(%r).pull_off_force)" % str(source / "data/scenes/hydrogel_film_two_term.json"))
    env = dict(os.environ, PYTHONPATH=str(target))
    r = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    path, version, force = r.stdout.split()
    assert path.startswith(str(target))
    assert float(force) < 0
    # The version of the installed metadata is the CMake project's, like the module's.
    assert version == layerjkr_version(source)
    dist = list(target.glob("layerjkr-*.dist-info"))
    assert [d.name for d in dist] == ["layerjkr-%s.dist-info" % version]
    # Typed: the PEP 561 marker and the compiled module's stub are installed beside it.
    assert (target / "layerjkr" / "py.typed").exists() and (target / "layerjkr" / "_core.pyi").exists()


def layerjkr_version(source):
    cmake = (source / "CMakeLists.txt").read_text()
    return re.search(r"project\(\s*layerjkr\s+VERSION\s+([0-9.]+)", cmake).group(1)
