#!/usr/bin/env bash
# Fuzzes every reader of outside files with libFuzzer for a bounded time each: the LAS reader
# (tests/fuzz/fuzz_las_reader.cpp), the CityJSON reader, the CityGML path and the mesh-file path of
# the scene (fuzz_cityjson_reader, fuzz_citygml_reader, fuzz_mesh_reader), fish-eye images
# (fuzz_fisheye_image), point tables (fuzz_point_table) and the far field's pyramid files
# (fuzz_pyramid_file). FUZZ_SECONDS (default 30) per target,
# one process each; FUZZ_TARGETS (default: all) picks some. Seeds are the small sample files in
# ../shared/sample_data (LAS, city3d) and Debian's assimp-testmodels when present, plus tiny files
# written here (nothing binary is committed). Exits non-zero when a fuzzer finds a crash, sanitizer
# report, leak or hang; the input is left in build-fuzz/artifacts. Needs clang, python3 and
# gdal_translate; no network.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
targets=(${FUZZ_TARGETS:-fuzz_las_reader fuzz_cityjson_reader fuzz_citygml_reader fuzz_mesh_reader fuzz_fisheye_image
  fuzz_point_table fuzz_pyramid_file})

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKYVIEW_BUILD_FUZZ=ON \
  -DSKYVIEW_BUILD_TESTS=OFF -DSKYVIEW_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz --target "${targets[@]}" -j"${FUZZ_JOBS:-$(nproc)}"

artifacts=build-fuzz/artifacts
mkdir -p "$artifacts"
shared=../shared/sample_data

# Seeds, one corpus folder per target.
seed_las() {
  local corpus=$1
  if [ -d "$shared/las" ]; then
    find "$shared/las" -maxdepth 1 -type f \( -name '*.las' -o -name '*.laz' \) -size -256k -exec cp -f {} "$corpus"/ \;
  fi
  # Minimal valid files: LAS 1.2 format 0 with one point, LAS 1.2 format 1 with a GeoTIFF key VLR,
  # LAS 1.4 format 6 with an OGC WKT EVLR.
  python3 - "$corpus" <<'EOF'
import os, struct, sys

def las(minor, fmt, points, vlrs=b"", nvlr=0, evlr=b"", nevlr=0):
    base = {0: 20, 1: 28, 6: 30}[fmt]
    hsize = {2: 227, 4: 375}[minor]
    offset = hsize + len(vlrs)
    h = bytearray(hsize)
    h[0:4] = b"LASF"
    h[24], h[25] = 1, minor
    h[26:58] = b"skyview fuzz.sh".ljust(32, b"\0")
    struct.pack_into("<HIIBHI", h, 94, hsize, offset, nvlr, fmt, base, len(points) if fmt < 6 else 0)
    struct.pack_into("<3d3d6d", h, 131, 0.01, 0.01, 0.01, 0, 0, 0, 1, 0, 1, 0, 1, 0)
    body = b""
    for x, y, z in points:
        rec = struct.pack("<3iH", x, y, z, 100) + bytes([0x09 if fmt < 6 else 0x11, 2, 2])
        body += rec.ljust(base, b"\0")
    if minor == 4:
        struct.pack_into("<QIQ", h, 235, offset + len(body), nevlr, len(points))
    return bytes(h) + vlrs + body + evlr

def vlr(user, rid, data):
    return struct.pack("<H16sHH32s", 0, user, rid, len(data), b"") + data

def evlr(user, rid, data):
    return struct.pack("<H16sHQ32s", 0, user, rid, len(data), b"") + data

geokeys = struct.pack("<4H", 1, 1, 0, 1) + struct.pack("<4H", 3072, 0, 1, 32633)
wkt = b'GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]]\0'
out = sys.argv[1]
files = {
    "gen_1_2_f0.las": las(2, 0, [(100, 200, 300)]),
    "gen_1_2_f1_geokeys.las": las(2, 1, [(1, 2, 3), (-4, 5, -6)], vlr(b"LASF_Projection", 34735, geokeys), 1),
    "gen_1_4_f6_wkt.las": las(4, 6, [(7, 8, 9)], evlr=evlr(b"LASF_Projection", 2112, wkt), nevlr=1),
}
for name, data in files.items():
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)
EOF
}

seed_cityjson() {
  local corpus=$1
  [ -f "$shared/city3d/rotterdam_subset.city.json" ] && cp -f "$shared/city3d/rotterdam_subset.city.json" "$corpus"/
  # A closed solid with a hole in two LoDs, a 1.0 template instance, a CityJSONSeq of one feature.
  cat >"$corpus/gen_solid.json" <<'EOF'
{"type":"CityJSON","version":"2.0","transform":{"scale":[0.5,0.5,0.5],"translate":[1000,2000,3]},
"metadata":{"referenceSystem":"https://www.opengis.net/def/crs/EPSG/0/25833"},
"CityObjects":{"b":{"type":"Building","geometry":[{"type":"Solid","lod":"2","boundaries":[[[[0,3,2,1],[4,5,6,7]],
[[0,1,9,8]],[[1,2,10,9]]]]},{"type":"MultiSurface","lod":"1","boundaries":[[[0,1,2]]]}]},"p":{"type":"Building","children":["b"]}},
"vertices":[[0,0,0],[40,0,0],[40,20,0],[0,20,0],[16,4,0],[24,4,0],[24,12,0],[16,12,0],[0,0,14],[40,0,14],[40,20,14]]}
EOF
  cat >"$corpus/gen_template.json" <<'EOF'
{"type":"CityJSON","version":"1.0","CityObjects":{"t":{"type":"SolitaryVegetationObject","geometry":[
{"type":"GeometryInstance","template":0,"boundaries":[0],"transformationMatrix":[2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1]}]}},
"vertices":[[10.5,20.25,3.0]],"geometry-templates":{"templates":[{"type":"MultiSolid","lod":1,"boundaries":[[[[[0,1,2,3]]]]]}],
"vertices-templates":[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}}
EOF
  printf '%s\n%s\n' \
    '{"type":"CityJSON","version":"2.0","transform":{"scale":[0.01,0.01,0.01],"translate":[0,0,0]},"CityObjects":{},"vertices":[]}' \
    '{"type":"CityJSONFeature","id":"a","CityObjects":{"a":{"type":"Building","geometry":[{"type":"CompositeSurface","lod":"1.2","boundaries":[[[0,1,2]]]}]}},"vertices":[[0,0,0],[100,0,0],[0,100,0]]}' \
    >"$corpus/gen_seq.jsonl"
}

seed_citygml() {
  local corpus=$1
  [ -f "$shared/city3d/cube_lod2.gml" ] && cp -f "$shared/city3d/cube_lod2.gml" "$corpus"/
  cat >"$corpus/gen_building.gml" <<'EOF'
<CityModel xmlns="http://www.opengis.net/citygml/2.0" xmlns:gml="http://www.opengis.net/gml" xmlns:bldg="http://www.opengis.net/citygml/building/2.0">
<gml:boundedBy><gml:Envelope srsName="urn:adv:crs:ETRS89_UTM32*DE_DHHN92_NH"><gml:lowerCorner>0 0 0</gml:lowerCorner><gml:upperCorner>9 9 9</gml:upperCorner></gml:Envelope></gml:boundedBy>
<cityObjectMember><bldg:Building gml:id="b"><bldg:boundedBy><bldg:RoofSurface><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>
<gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>0 0 9 9 0 9 9 9 9 0 9 9 0 0 9</gml:posList></gml:LinearRing></gml:exterior>
<gml:interior><gml:LinearRing><gml:posList>3 3 9 3 6 9 6 6 9 3 3 9</gml:posList></gml:LinearRing></gml:interior></gml:Polygon>
</gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:RoofSurface></bldg:boundedBy></bldg:Building></cityObjectMember>
</CityModel>
EOF
}

seed_mesh() {
  local corpus=$1 models=/usr/share/assimp/models
  # The first byte picks the format: 0 OBJ, 1 PLY, 2 STL, 3 OFF, 4 glTF, 5 GLB.
  local pick file
  for pick in "0 OBJ/box.obj" "1 PLY/cube.ply" "1 PLY/cube_binary.ply" "2 STL/triangle_with_two_solids.stl" \
    "3 OFF/Cube.off" "4 glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf" "5 glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"; do
    file=${pick#* }
    [ -f "$models/$file" ] && { printf "\\x0${pick%% *}"; cat "$models/$file"; } >"$corpus/$(basename "$file")"
  done
  printf '\x00v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nl 1 2\n' >"$corpus/gen_nan.obj"
}

# libcitygml 2.4 (with Xerces) and Assimp 5.2 leak what they had parsed when a file breaks off:
# their leaks, not ours, which LeakSanitizer still reports. libcitygml leaks on nearly every broken
# document, and libFuzzer's leak check after each would slow that target a hundredfold: there it is
# off (its unit tests run under ASan with LeakSanitizer instead), with room for what piles up.
suppressions=build-fuzz/lsan.supp
printf 'leak:libcitygml.so\nleak:libxerces-c\nleak:libassimp.so\n' >"$suppressions"

# Fish-eye images: a tiny circular "photograph" as PNG and JPEG, a mask; point tables: CSVs. Both
# corpora at once (one script writes them).
seed_fisheye_and_points() {
  local images=build-fuzz/corpus/fuzz_fisheye_image points=build-fuzz/corpus/fuzz_point_table
  mkdir -p "$images" "$points"
  set -- "$images" "$points"
python3 - "$1" "$2" <<'EOF'
import math, os, struct, sys, zlib

def png(path, w, h, channels, pixel):
    raw = b"".join(b"\0" + bytes(v for x in range(w) for v in pixel(x, y)) for y in range(h))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    colour = {1: 0, 3: 2}[channels]
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, colour, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

def photo(x, y):
    if math.hypot(x - 20, y - 16) > 14: return (0, 0, 0)
    return (90, 90, 95) if x < 12 else (70, 130, 215)

images, points = sys.argv[1], sys.argv[2]
png(os.path.join(images, "photo.png"), 40, 32, 3, photo)
png(os.path.join(images, "mask.png"), 24, 24, 1, lambda x, y: (255 if math.hypot(x - 11.5, y - 11.5) < 9 else 0,))
seeds = {"xy.csv": "name,x,y\na,1.5,2\nb,abc,3\n", "lonlat.csv": "id;lon;lat\n1;11.97;57.7\n",
         "quoted.csv": '"x","y","note"\n"1","2","a, b"\n', "empty.csv": "x,y\n"}
for name, text in seeds.items():
    with open(os.path.join(points, name), "w") as f:
        f.write(text)
EOF
  gdal_translate -q -of JPEG "$images/photo.png" "$images/photo.jpg" 2>/dev/null || true
  rm -f "$images"/*.aux.xml
}

# Pyramid files (the format in include/skyview/tiling/pyramid_file.h): a 3 x 2 raster's two levels
# from level 1, one with a NaN cell and a source text.
seed_pyramid() {
python3 - "$1" <<'EOF'
import math, os, struct, sys

def pyramid(width, height, levels, lo, hi, source, minima=None):
    flags = 1 if minima else 0
    body = b"SKYVPYRM" + struct.pack("<6I", 2, 1, width, height, len(levels), flags) + struct.pack("<2d", lo, hi)
    body += struct.pack("<I", len(source)) + source
    body += b"".join(struct.pack("<d", relief) for relief, _ in levels)
    body += b"".join(struct.pack("<%df" % len(cells), *cells) for _, cells in levels)
    body += b"".join(struct.pack("<%df" % len(cells), *cells) for cells in (minima or []))
    h = 0xcbf29ce484222325
    for b in body:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return body + struct.pack("<Q", h)

with open(os.path.join(sys.argv[1], "small.bin"), "wb") as f:
    f.write(pyramid(3, 2, [(2.0, [1.0, 3.0]), (2.0, [3.0])], 1.0, 3.0, b'{"input":"dsm.tif"}'))
with open(os.path.join(sys.argv[1], "nodata.bin"), "wb") as f:
    f.write(pyramid(3, 2, [(0.0, [math.nan, 0.5]), (0.0, [0.5])], 0.5, 0.5, b""))
with open(os.path.join(sys.argv[1], "minima.bin"), "wb") as f:
    f.write(pyramid(3, 2, [(2.0, [1.0, 3.0]), (2.0, [3.0])], 1.0, 3.0, b"", [[1.0, 1.0], [1.0]]))
EOF
}

status=0
for target in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$target
  mkdir -p "$corpus"
  case $target in
    fuzz_las_reader) seed_las "$corpus" ;;
    fuzz_cityjson_reader) seed_cityjson "$corpus" ;;
    fuzz_citygml_reader) seed_citygml "$corpus" ;;
    fuzz_mesh_reader) seed_mesh "$corpus" ;;
    fuzz_fisheye_image | fuzz_point_table) seed_fisheye_and_points ;;
    fuzz_pyramid_file) seed_pyramid "$corpus" ;;
  esac
  extra=()
  [ "$target" = fuzz_citygml_reader ] && extra=(-detect_leaks=0 -rss_limit_mb=6144)
  echo "fuzzing $target for ${seconds}s ($(find "$corpus" -type f | wc -l) inputs in $corpus)"
  log=build-fuzz/$target.log
  target_status=0
  LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$suppressions} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} \
    CPL_LOG=/dev/null build-fuzz/$target "$corpus" -artifact_prefix="$artifacts/$target-" \
    -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 "${extra[@]}" \
    >"$log" 2>&1 || target_status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  echo "$target: ${execs:-unknown} executions, ${rate:-unknown} exec/s, limit ${seconds}s (log: $log)"
  if [ "$target_status" -ne 0 ]; then
    tail -n 80 "$log"
    echo "$target FAILED (exit $target_status); reproduce with: build-fuzz/$target $artifacts/$target-<file>" >&2
    status=1
  fi
done
exit $status
