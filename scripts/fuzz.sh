#!/usr/bin/env bash
# Fuzzes the LAS reader (tests/fuzz/fuzz_las_reader.cpp) with libFuzzer for a bounded time:
# FUZZ_SECONDS (default 60), one process. Seeds are the small sample LAS/LAZ files in
# ../shared/sample_data/las when present plus tiny LAS files written here (nothing binary is
# committed). Exits non-zero when the fuzzer finds a crash, sanitizer report, leak or hang;
# the input is left in build-fuzz/artifacts. Needs clang and python3; no network.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSKYVIEW_BUILD_FUZZ=ON \
  -DSKYVIEW_BUILD_TESTS=OFF -DSKYVIEW_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz --target fuzz_las_reader -j"${FUZZ_JOBS:-$(nproc)}"

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

echo "fuzzing the LAS reader for ${seconds}s ($(find "$corpus" -type f | wc -l) inputs in $corpus)"
log=build-fuzz/fuzz.log
status=0
ASAN_OPTIONS=${ASAN_OPTIONS:-} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} CPL_LOG=/dev/null \
  build-fuzz/fuzz_las_reader "$corpus" -artifact_prefix="$artifacts/" -max_total_time="$seconds" \
  -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 >"$log" 2>&1 || status=$?
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
echo "fuzz_las_reader: ${execs:-unknown} executions, ${rate:-unknown} exec/s, limit ${seconds}s (log: $log)"
if [ "$status" -ne 0 ]; then
  tail -n 80 "$log"
  echo "fuzz_las_reader FAILED (exit $status); reproduce with: build-fuzz/fuzz_las_reader $artifacts/<file>" >&2
  exit 1
fi
