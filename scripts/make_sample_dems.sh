#!/usr/bin/env bash
# Regenerates the synthetic rasters in sample_dems/ with skyview's own generator.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${SKYVIEW:-./build/skyview}
"$exe" synth city sample_dems/city.tif --size 401 --cell 1 --crs EPSG:32633 --overwrite -q
"$exe" synth mountains sample_dems/mountains.tif --size 601 --cell 10 --crs EPSG:32633 --overwrite -q
# A 128 m district as a city hands it over: a classified LiDAR survey and footprints with heights.
"$exe" synth lidar sample_dems/district.las --size 128 --cell 1 --crs EPSG:32633 --overwrite -q
"$exe" synth footprints sample_dems/district_footprints.geojson --size 128 --cell 1 --crs EPSG:32633 --overwrite -q
