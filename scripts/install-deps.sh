#!/usr/bin/env bash
# Installs the Debian 12 packages skyview builds and tests with (run as root).
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libgdal-dev gdal-bin libnetcdf-dev libgeographiclib-dev libopencv-dev libpcl-dev libembree-dev libtbb-dev libgeos-dev
  libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev
  # Scenes: CityGML (libcitygml's CMake target also names libGL.so and libGLU.so)
  libcitygml-dev libglu1-mesa-dev libgl-dev
  libassimp-dev assimp-testmodels  # mesh files (OBJ, PLY, glTF...); the models are read by the tests
  clang clang-format libclang-rt-14-dev  # libFuzzer and sanitizer runtimes (only recommended by clang)
  python3  # scripts/fuzz.sh writes its seed LAS files with it
  libopenmpi-dev openmpi-bin  # optional at build time: mpirun ranks share the tiles of a --tiles-dir run
  tzdata  # IANA zone rules read by skyview sun --tz (src/solar/time_zone.cpp)
  # The Python module (-DSKYVIEW_PYTHON=ON, docs/python.md) and its pytest suite
  pybind11-dev python3-dev python3-numpy python3-pytest python3-setuptools python3-venv python3-pip
  python3-xarray python3-dask python3-distributed python3-gdal
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
