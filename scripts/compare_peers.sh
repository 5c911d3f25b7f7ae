#!/usr/bin/env bash
# Speed and accuracy of skyview beside the peer tools Debian 12 packages, on one raster and one
# machine: SAGA 8.5 (ta_lighting "Sky View Factor", both of its methods) and GRASS 8.2
# (r.horizon, with svf summed by r.mapcalc). Every svf is judged by skyview's ray-cast reference
# at the same directions, with `skyview compare`, over all cells and over flat cells (slope at
# most 1 degree: SAGA tilts its svf by its own slope estimate, which walls turn negative).
#
# usage: scripts/compare_peers.sh RASTER OUT_DIR [DIRECTIONS] [RADIUS_M]
#   DIRECTIONS: a multiple of 4 (GRASS counts azimuths from east, skyview and SAGA from north), default 32
#   RADIUS_M:   the peers' search radius, default the raster's diagonal (unlimited, like the sweep's)
# Installs saga and grass-core if missing (as root). Not part of the tests: SAGA and GRASS take
# minutes where skyview takes seconds. Writes OUT_DIR/peers.md and OUT_DIR/peers.json.
# REUSE=1 keeps every output (and its recorded time) already in OUT_DIR; delete one to redo it.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
raster="$(realpath "$1")"
out="$(mkdir -p "$2" && realpath "$2")"
directions="${3:-32}"
if (( directions % 4 != 0 )); then echo "compare_peers: DIRECTIONS must be a multiple of 4" >&2; exit 2; fi
skyview="$here/build/skyview"
[ -x "$skyview" ] || { echo "compare_peers: build skyview first (bash scripts/quickstart.sh)" >&2; exit 2; }

missing=()
for p in saga grass-core; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null
fi

# Size and cell size from the raster (projected CRS in metres).
read -r width height cell < <(gdalinfo -json "$raster" | python3 -c '
import json, sys
j = json.load(sys.stdin)
print(j["size"][0], j["size"][1], abs(j["geoTransform"][1]))')
radius="${4:-$(python3 -c "print(round(($width**2 + $height**2) ** 0.5 * $cell))")}"
cell_dirs=$(( width * height * directions ))
echo "raster $raster: ${width} x ${height} cells of ${cell} m, $directions directions, peers' radius ${radius} m" >&2

results="$out/results.tsv"
: >"$results"
# Runs a command that writes $out/NAME.tif and records its wall time in $out/NAME.time (kept with REUSE=1).
timed() {
  local name="$1" start end
  shift
  if [ "${REUSE:-0}" = 1 ] && [ -f "$out/$name.tif" ] && [ -f "$out/$name.time" ]; then return 0; fi
  rm -f "$out/$name".*
  start=$(date +%s.%N)
  "$@" >"$out/$name.log" 2>&1 || { cat "$out/$name.log" >&2; return 1; }
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.2f}')" >"$out/$name.time"
}
# name, settings, the reference's band that holds the tool's definition of svf (1 svf, 2 svf_surface)
judge() {
  local name="$1" settings="$2" band="$3"
  "$skyview" compare "$out/$name.tif" "$out/reference.tif" --ref-band "$band" -q --json "$out/$name.all.json"
  "$skyview" compare "$out/$name.tif" "$out/reference.tif" --dem "$raster" --max-slope 1 -q --json "$out/$name.flat.json"
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$settings" "$(cat "$out/$name.time")" "$band" "$out/$name.all.json" \
    "$out/$name.flat.json" >>"$results"
  echo "$name: $(cat "$out/$name.time") s" >&2
}

# Bands 1 and 2 (svf, svf_surface) are all the judges read; the ray cast's lowest angles would triple its time.
timed reference "$skyview" svf "$raster" "$out/reference.tif" --method raycast --rays 0 --directions "$directions" \
  --products svf,svf_surface --overwrite -q
echo "reference (ray cast): $(cat "$out/reference.time") s" >&2

timed skyview_sweep "$skyview" svf "$raster" "$out/skyview_sweep.tif" --directions "$directions" --overwrite -q
judge skyview_sweep "skyview sweep, unlimited radius, 64 exact near steps, all five bands" 1
timed skyview_sweep_svf "$skyview" svf "$raster" "$out/skyview_sweep_svf.tif" --directions "$directions" --products svf --overwrite -q
judge skyview_sweep_svf "skyview sweep, as above, \`--products svf\`" 1
timed skyview_march "$skyview" svf "$raster" "$out/skyview_march.tif" --method march --radius "$radius" --directions "$directions" --overwrite -q
judge skyview_march "skyview march, radius $radius m" 1

# SAGA tilts its svf by its own slope estimate: judged against svf_surface over all cells, against
# svf over flat cells (where the two agree).
for method in 0 1; do
  label=$([ $method = 0 ] && echo "cell size" || echo "multi scale")
  timed "saga_m$method" saga_cmd ta_lighting 3 -DEM "$raster" -SVF "$out/saga_m$method.tif" -RADIUS "$radius" -NDIRS "$directions" -METHOD $method
  judge "saga_m$method" "SAGA 8.5 Sky View Factor, METHOD $method ($label), radius $radius m" 2
done

# GRASS: a throwaway location in the raster's CRS; r.horizon and r.mapcalc are timed, import and export not.
step=$(python3 -c "print(360 / $directions)")
if ! [ "${REUSE:-0}" = 1 ] || ! [ -f "$out/grass.tif" ] || ! [ -f "$out/grass.time" ]; then
gisdb="$out/grassdb"
rm -rf "$gisdb"
grass -c "$raster" "$gisdb/loc" -e >/dev/null 2>&1
cat >"$out/grass_svf.sh" <<EOF
set -e
r.in.gdal -o input="$raster" output=dem --overwrite --quiet
g.region raster=dem
start=\$(date +%s.%N)
r.horizon -d elevation=dem step=$step maxdistance=$radius output=hor --overwrite --quiet
terms=\$(g.list raster pattern='hor_*' separator=' ' | tr ' ' '\n' | awk '{printf "%s(sin(max(%s,0)))^2", (NR>1?" + ":""), \$1}')
r.mapcalc "svf = 1.0 - (\$terms) / $directions" --overwrite --quiet
end=\$(date +%s.%N)
python3 -c "print(f'{\$end - \$start:.2f}')" >"$out/grass.time"
r.out.gdal -c input=svf output="$out/grass.tif" type=Float64 --overwrite --quiet
EOF
grass "$gisdb/loc/PERMANENT" --exec bash "$out/grass_svf.sh" >"$out/grass.log" 2>&1 || { cat "$out/grass.log" >&2; exit 1; }
rm -rf "$gisdb"
fi
judge grass "GRASS 8.2 r.horizon (step $step°, maxdistance $radius m) + r.mapcalc" 1

python3 - "$results" "$out" "$raster" "$cell_dirs" "$directions" "$(cat "$out/reference.time")" <<'EOF'
import json, sys
results, out, raster, cell_dirs, directions, ref_seconds = sys.argv[1:]
rows = []
for line in open(results):
    name, settings, seconds, band, all_json, flat_json = line.rstrip("\n").split("\t")
    a, f = json.load(open(all_json)), json.load(open(flat_json))
    rows.append({"tool": name, "settings": settings, "seconds": float(seconds), "reference_band": int(band),
                 "cell_directions_per_second": int(cell_dirs) / float(seconds), "all": a, "flat": f})
json.dump({"raster": raster, "directions": int(directions), "reference_seconds": float(ref_seconds),
           "results": rows}, open(out + "/peers.json", "w"), indent=2)
with open(out + "/peers.md", "w") as md:
    md.write(f"Raster `{raster.split('/')[-1]}`, {directions} directions; reference: skyview ray cast at the same "
             f"directions ({float(ref_seconds):.1f} s). Wall times of whole runs on this machine, both cores. svf "
             f"errors against the reference over all cells (SAGA against svf_surface, since it tilts its svf by "
             f"its own slope; * marks those) and over the {rows[0]['flat']['cells']} of {rows[0]['all']['cells']} "
             f"cells of slope at most 1°.\n\n")
    md.write("| tool and settings | time (s) | M cell-dirs/s | svf p99, all | svf p99, flat | svf RMSE, flat | svf bias, flat |\n")
    md.write("|---|---:|---:|---:|---:|---:|---:|\n")
    for r in rows:
        star = "*" if r["reference_band"] != 1 else ""
        md.write(f"| {r['settings']} | {r['seconds']:.2f} | {r['cell_directions_per_second'] / 1e6:.2f} | "
                 f"{r['all']['p99_abs']:.4f}{star} | {r['flat']['p99_abs']:.4f} | {r['flat']['rmse']:.4f} | "
                 f"{r['flat']['bias']:+.4f} |\n")
print(open(out + "/peers.md").read())
EOF
