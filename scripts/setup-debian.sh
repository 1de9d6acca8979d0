#!/usr/bin/env bash
# Installs the Debian 12 packages radchain needs, when they are missing. Idempotent; works as root or
# through sudo; never touches the network when everything is already installed.
set -euo pipefail

packages=(
  g++ make cmake pkg-config git ca-certificates
  libboost-dev            # Boost.DLL (plugins), Boost.Math (roots, distributions); header-only in 1.74
  libtomlplusplus-dev     # sensor files
  libeigen3-dev           # spectra
  libudunits2-dev         # unit strings
  libfmt-dev libcli11-dev nlohmann-json3-dev
  libtbb-dev              # thread pool for sweeps and catalogues
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox             # plots of sweeps and MTF curves
  libopenimageio-dev      # radchain render: FITS/PNG/TIFF output through OpenImageIO 2.4
  openimageio-tools       # iinfo/oiiotool, to inspect rendered frames and their FITS headers
  libfftw3-dev            # radchain render: PSFs and MTFs applied in the Fourier domain
  libcfitsio-dev          # FITS frames: OpenImageIO 2.4's FITS plugin shifts rows (framework/imaging/src/image_io.cpp)
  python3-dev python3-pybind11 pybind11-dev   # `import radchain` (python/, docs/python.md), built for /usr/bin/python3
  python3-numpy python3-pandas python3-pytest # its arrays and tables, and its tests
  python3-synphot         # the independent photometry reference of the differential tests (python/tests)
  python3-astropy         # Result.quantity(): results as astropy Quantities (and the check of radchain's units against astropy's)
  python3-distributed python3-dask          # radchain.dask: sweeps and catalogues over a dask cluster (docs/python.md)
  python3-nbclient python3-nbformat python3-ipykernel python3-matplotlib   # examples/notebooks, run by the tests
  clang-14 libclang-rt-14-dev # the clang build and its libFuzzer harnesses (scripts/fuzz-smoke, docs/fuzzing.md)
  chromium fonts-dejavu-core  # the HTML report checked in a real browser, headless (tests/browser/check_report.py, docs/report.md)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "radchain setup: these Debian packages are missing and installing them needs root or sudo: ${missing[*]}" >&2
  exit 2
fi
echo "radchain setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -q
"${as_root[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
