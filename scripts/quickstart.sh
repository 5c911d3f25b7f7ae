#!/usr/bin/env bash
# Quick start: installs what is missing, builds skyview (Release) and computes the sky-view
# factor of the bundled synthetic city, writing out/city_svf.tif and out/city_svf.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSKYVIEW_BUILD_TESTS=OFF -DSKYVIEW_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target skyview_cli
mkdir -p out
./build/skyview svf sample_dems/city.tif out/city_svf.tif --preview out/city_svf.png --overwrite
echo "Wrote out/city_svf.tif (bands: svf, svf_surface, sky_visibility, openness_positive, openness_negative) and out/city_svf.png"
