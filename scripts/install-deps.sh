#!/usr/bin/env bash
# Installs the Debian 12 packages layerjkr builds, tests and plots with (clang, clang-tidy
# and libclang-rt-14-dev for the fuzz and tidy presets).
# libzip-dev's CMake package (libzip::zip) also imports the zipcmp, zipmerge and ziptool
# programs and fails without them (Debian packages them separately).
# python3-selenium, chromium and chromium-driver run the map report's test in a headless browser
# (fonts-liberation: with --no-install-recommends chromium would have no font to draw text with).
# The Python module builds against Debian's /usr/bin/python3 and its packages (no PyPI needed).
# python3-pandas and python3-xarray: BatchResults.to_pandas and to_xarray (optional at run time).
# python3-nbclient, python3-nbformat and python3-ipykernel run examples/notebooks/afm_map.ipynb in the tests.
# python3-venv and patchelf: tools/bundle_wheel.py and the test that installs the wheel into a fresh venv.
# python3-scipy: python/bench/fit_vs_scipy.py, the per-curve comparison with scipy's least_squares.
# libhdf5-dev: afmformats' .h5 exports, read by the CLI (not linked into the library or the wheel).
# Runs apt-get directly as root (CI, containers) and through sudo otherwise.
set -euo pipefail
packages=(cmake ninja-build g++ libeigen3-dev libgsl-dev libboost-dev libceres-dev libmetis-dev
          catch2 libcli11-dev nlohmann-json3-dev libbenchmark-dev gnuplot-nox
          clang clang-tidy libclang-rt-14-dev libzip-dev zipcmp zipmerge ziptool zlib1g-dev libdeflate-dev pkg-config libssl-dev libhdf5-dev
          pybind11-dev python3-dev python3-pybind11 python3-numpy python3-pytest python3-setuptools
          python3-pip python3-matplotlib python3-dask python3-distributed python3-pandas python3-xarray
          python3-nbclient python3-nbformat python3-ipykernel python3-venv patchelf python3-scipy
          python3-selenium chromium chromium-driver fonts-liberation)
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  "${as_root[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
