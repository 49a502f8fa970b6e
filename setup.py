"""Builds layerjkr._core with the project's CMake (the same build as the C++ library and CLI)
and puts it into the package. LAYERJKR_CMAKE_BUILD_DIR reuses a configured build directory
(e.g. build/ of `cmake --preset default`) instead of configuring a fresh one."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The one version number: CMakeLists.txt's project(layerjkr VERSION x.y.z)."""
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(\s*layerjkr\s+VERSION\s+([0-9][0-9.]*)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt: no project(layerjkr VERSION ...)")
    return match.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = os.environ.get("LAYERJKR_CMAKE_BUILD_DIR")
        if build_dir:
            build_dir = pathlib.Path(build_dir).resolve()
        else:
            build_dir = pathlib.Path(self.build_temp).resolve() / "cmake"
            build_dir.mkdir(parents=True, exist_ok=True)
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-G", "Ninja",
                                   "-DCMAKE_BUILD_TYPE=Release", "-DLAYERJKR_BUILD_PYTHON=ON",
                                   "-DLAYERJKR_BUILD_TESTS=OFF", "-DLAYERJKR_BUILD_TOOLS=OFF",
                                   "-DLAYERJKR_BUILD_EXAMPLES=OFF", "-DLAYERJKR_BUILD_BENCHMARKS=OFF",
                                   "-DPython_EXECUTABLE=" + sys.executable])
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "layerjkr_python"])
        built = list((build_dir / "python" / "layerjkr").glob("_core*.so"))
        if len(built) != 1:
            raise RuntimeError("expected one built module in %s, found %s" % (build_dir, built))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(version=project_version(), ext_modules=[Extension("layerjkr._core", sources=[])], cmdclass={"build_ext": CMakeBuild})
