#!/usr/bin/env bash
# Quick start: installs what is missing, builds skyview (Release) and computes the sky-view
# factor of the bundled synthetic city, writing out/city_svf.tif and out/city_svf.png; then
# builds a height raster from the bundled LiDAR survey and footprints (out/district_dsm.tif).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSKYVIEW_BUILD_TESTS=OFF -DSKYVIEW_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target skyview_cli
mkdir -p out
./build/skyview svf sample_dems/city.tif out/city_svf.tif --preview out/city_svf.png --overwrite
./build/skyview dsm out/district_dsm.tif --points sample_dems/district.las \
  --footprints sample_dems/district_footprints.geojson --height-field height --base-field base --denoise --fill \
  --overwrite
echo "Wrote out/city_svf.tif (bands: svf, svf_surface, sky_visibility, openness_positive, openness_negative) and out/city_svf.png, and out/district_dsm.tif"
