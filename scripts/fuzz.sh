#!/usr/bin/env bash
# Fuzzes the readers of outside files with libFuzzer, each for a bounded time, FUZZ_SECONDS (default
# 60) apiece, one process: the LAS reader (tests/fuzz/fuzz_las_reader.cpp), fish-eye images
# (fuzz_fisheye_image.cpp) and point tables (fuzz_point_table.cpp). Seeds are the small sample
# LAS/LAZ files in ../shared/sample_data/las when present plus tiny files written here (nothing
# binary is committed). Exits non-zero when a fuzzer finds a crash, sanitizer report, leak or hang;
# the input is left in build-fuzz/artifacts. Needs clang, python3 and gdal_translate; no network.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKYVIEW_BUILD_FUZZ=ON \
  -DSKYVIEW_BUILD_TESTS=OFF -DSKYVIEW_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz --target fuzz_las_reader fuzz_fisheye_image fuzz_point_table -j"${FUZZ_JOBS:-$(nproc)}"

corpus=build-fuzz/corpus artifacts=build-fuzz/artifacts
mkdir -p "$corpus" "$artifacts"
samples=../shared/sample_data/las
if [ -d "$samples" ]; then
  find "$samples" -maxdepth 1 -type f \( -name '*.las' -o -name '*.laz' \) -size -256k \
    -exec cp -f {} "$corpus"/ \;
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

# Fish-eye images: a tiny circular "photograph" as PNG and JPEG, a mask; point tables: CSVs.
image_corpus=build-fuzz/corpus-fisheye points_corpus=build-fuzz/corpus-points
mkdir -p "$image_corpus" "$points_corpus"
python3 - "$image_corpus" "$points_corpus" <<'EOF'
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
gdal_translate -q -of JPEG "$image_corpus/photo.png" "$image_corpus/photo.jpg" 2>/dev/null || true
rm -f "$image_corpus"/*.aux.xml

failed=0
run_fuzzer() {  # name corpus
  local name=$1 dir=$2 log=build-fuzz/$1.log status=0
  echo "fuzzing $name for ${seconds}s ($(find "$dir" -type f | wc -l) inputs in $dir)"
  ASAN_OPTIONS=${ASAN_OPTIONS:-} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} CPL_LOG=/dev/null \
    build-fuzz/"$name" "$dir" -artifact_prefix="$artifacts/" -max_total_time="$seconds" \
    -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 >"$log" 2>&1 || status=$?
  local execs rate
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  echo "$name: ${execs:-unknown} executions, ${rate:-unknown} exec/s, limit ${seconds}s (log: $log)"
  if [ "$status" -ne 0 ]; then
    tail -n 80 "$log"
    echo "$name FAILED (exit $status); reproduce with: build-fuzz/$name $artifacts/<file>" >&2
    failed=1
  fi
}
run_fuzzer fuzz_las_reader "$corpus"
run_fuzzer fuzz_fisheye_image "$image_corpus"
run_fuzzer fuzz_point_table "$points_corpus"
exit "$failed"
