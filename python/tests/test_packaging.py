"""pip install . of the package (pyproject.toml + setup.py), on a copy of the source tree so
that nothing is written into the real one, reusing the configured build directory
(LAYERJKR_CMAKE_BUILD_DIR) so the test does not rebuild the library."""
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import zipfile

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


SYSTEM_LIBRARIES = re.compile(r"^(ld-linux[-\w.]*|libc|libm|libdl|librt|libpthread|libgcc_s|libstdc\+\+)\.so(\.\d+)*$")


def readelf_dynamic(path):
    """(NEEDED sonames, RUNPATH) of a shared object, from binutils' readelf -d."""
    out = subprocess.run(["readelf", "-d", str(path)], capture_output=True, text=True, check=True).stdout
    needed = re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", out)
    runpath = re.findall(r"\((?:RUNPATH|RPATH)\)\s+Library (?:runpath|rpath): \[([^\]]+)\]", out)
    return needed, runpath


def test_the_wheel_is_self_contained_and_installs_into_a_fresh_venv(source, tmp_path):
    # Issue 36: a wheel that needs nothing beyond glibc, libstdc++, libgcc and numpy.
    for tool in ("patchelf", "readelf", "ldd"):
        if shutil.which(tool) is None:
            pytest.skip("%s is not installed (scripts/install-deps.sh installs it)" % tool)
    build_dir = pathlib.Path(os.environ.get("LAYERJKR_BUILD_DIR", source / "build"))
    if not (build_dir / "CMakeCache.txt").exists():
        pytest.skip("no configured build directory at %s" % build_dir)
    tree = tmp_path / "src"
    shutil.copytree(source, tree, ignore=shutil.ignore_patterns(".git", "build", "build-*", "*.egg-info", "__pycache__"))
    env = dict(os.environ, LAYERJKR_CMAKE_BUILD_DIR=str(build_dir))
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps", "--no-index",
                        "-w", str(tmp_path / "dist"), str(tree)], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    plain = next((tmp_path / "dist").glob("layerjkr-*.whl"))
    r = subprocess.run([sys.executable, str(source / "tools" / "bundle_wheel.py"), str(plain), "-o", str(tmp_path / "house")],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    wheel = pathlib.Path(r.stdout.strip())
    assert re.search(r"-manylinux_2_\d+_\w+\.whl$", wheel.name)
    # Every shared object in the wheel needs only system libraries and the ones bundled beside it.
    unpacked = tmp_path / "unpacked"
    with zipfile.ZipFile(wheel) as z:
        z.extractall(unpacked)
        names = z.namelist()
    bundled = {p.name for p in (unpacked / "layerjkr.libs").glob("*.so*")}
    # Issue 43: each bundled library carries a hash of its content in its name, as auditwheel
    # names them, so that another package's copy of the same soname cannot stand in for it.
    original = {re.sub(r"-[0-9a-f]{8}(?=\.so)", "", b): b for b in bundled}
    assert all(re.search(r"-[0-9a-f]{8}\.so", b) for b in bundled), bundled
    assert {"libgsl.so.27", "libglog.so.1", "libcholmod.so.3", "libdeflate.so.0", "libcrypto.so.3"} <= set(original)
    objects = list(unpacked.rglob("*.so*"))
    for so in objects:
        needed, runpath = readelf_dynamic(so)
        outside = [n for n in needed if n not in bundled and not SYSTEM_LIBRARIES.match(n)]
        assert not outside, (so.name, outside)
        expected = "$ORIGIN/../layerjkr.libs" if so.parent.name == "layerjkr" else "$ORIGIN"
        assert runpath == [expected], (so.name, runpath)
        if so.parent.name == "layerjkr.libs":
            soname = re.findall(r"\(SONAME\)\s+Library soname: \[([^\]]+)\]",
                                subprocess.run(["readelf", "-d", str(so)], capture_output=True, text=True).stdout)
            assert soname == [so.name], (so.name, soname)
    # The tag: the newest GLIBC symbol version any object needs (objdump's version references,
    # read independently of the tool's readelf), not the build machine's glibc.
    newest = 0
    for so in objects:
        refs = subprocess.run(["objdump", "-p", str(so)], capture_output=True, text=True, check=True).stdout
        newest = max([newest] + [int(m) for m in re.findall(r"\bGLIBC_2\.(\d+)", refs)])
    assert re.search(r"-manylinux_2_%d_\w+\.whl$" % newest, wheel.name), (wheel.name, newest)
    # The licences of what is bundled ship with it, and BUNDLED.txt names each library's package,
    # version and where its sources are; each name's hash is the original file's.
    assert "layerjkr.libs/licenses/BUNDLED.txt" in names
    assert sum(1 for n in names if n.endswith(".copyright")) >= 10
    rows = [line.split("\t") for line in (unpacked / "layerjkr.libs" / "licenses" / "BUNDLED.txt").read_text().splitlines()
            if line.count("\t") == 5]
    assert {r[0] for r in rows} == bundled
    for name, soname, path, package, version, where in rows:
        assert re.sub(r"-[0-9a-f]{8}(?=\.so)", "", name) == soname
        assert hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()[:8] in name
        assert package != "-" and version != "?" and where.startswith("https://sources.debian.org/src/"), (name, where)
    # A fresh venv (Debian's numpy, matplotlib, pandas, xarray and pytest seen through
    # --system-site-packages; no layerjkr anywhere else) installs it, and the package's tests pass there.
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    r = subprocess.run([str(python), "-m", "pip", "install", "--no-index", "--no-deps", str(wheel)],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    clean = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "LD_LIBRARY_PATH")}
    r = subprocess.run([str(python), "-c", "import layerjkr, layerjkr._core as c; print(layerjkr.__file__); print(c.__file__)"],
                       capture_output=True, text=True, env=clean, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    package_file, core = r.stdout.split()
    assert package_file.startswith(str(venv))
    ldd = subprocess.run(["ldd", core], capture_output=True, text=True, check=True).stdout
    for line in ldd.splitlines():
        m = re.match(r"\s*(\S+) => (\S+)", line)
        if m and not SYSTEM_LIBRARIES.match(m.group(1)) and not m.group(1).startswith("linux-vdso"):
            assert "/layerjkr.libs/" in m.group(2), line  # resolved inside the wheel, not from /lib
    r = subprocess.run([str(python), "-m", "pytest", "-q", "-p", "no:cacheprovider", "--basetemp", str(tmp_path / "t"),
                        str(source / "python" / "tests" / "test_package.py")],
                       capture_output=True, text=True, env=dict(clean, MPLBACKEND="Agg"), cwd=tmp_path)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
