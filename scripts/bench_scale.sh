#!/usr/bin/env bash
# Scale benchmark (issue 22 item 6): load time, BVH build time, peak memory and rays per second
# of a 1-2 million triangle Blender-made apartment with a few hundred textures, against the
# small rooms (the generated mini room, preset mini seed 1, and tests/data/gltf/blender_lit_room).
#
# Usage: scripts/bench_scale.sh [--phyir BIN] [--out DIR] [--scene-dir DIR] [--triangles N]
#          [--textures N] [--seed S] [--texture-size PX] [--repeats R] [--width W] [--height H]
#          [--spp S] [--variants LIST] [--help]
#   --phyir BIN        phyir binary (default build/cli/phyir)
#   --out DIR          results folder (default bench-scale)
#   --scene-dir DIR    the big room's folder; generated there with Blender when big_room.gltf is
#                      absent (default DIR/big_room; keep it out of the repo, it is ~50 MB)
#   --triangles, --textures, --seed, --texture-size
#                      scripts/blender/make_big_room.py's arguments (1500000, 300, 1, 512)
#   --repeats R        runs of every measurement (default 3), interleaved across scenes
#   --width/--height/--spp   the phyir render (default 512 x 256, 16 spp, equirect)
#   --variants LIST    gltf-transform variants of the big room also measured, comma-separated
#                      from draco,meshopt,quantize,instance, or none (default instance); made
#                      by scripts/gltf_variants.sh into SCENE_DIR/variants when absent
# Per scene and run: `/usr/bin/time -v phyir scenes info` (wall s, peak RSS), `phyir render`
# (render.json load/build seconds and rays/s, peak RSS) and `phyir bench throughput` (256 x 128,
# 16 spp, plus raw Embree on 200k replayed rays). Writes DIR/runs.csv (every run, with the
# 1-minute load average before it), DIR/scale.csv and DIR/scale.json (per scene: minimum times
# and peak RSS, maximum rays/s, texture memory with every mip level: `scenes info`'s bytes, or
# float RGBA for binaries that do not report them) and DIR/scale.md (the table of
# docs/performance.md, "Large scenes"). Needs blender (only to generate), node (variants),
# /usr/bin/python3. Exit status 0 = measured, 1 = a step failed, 2 = usage.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

phyir=$root/build/cli/phyir out=bench-scale scene_dir=""
triangles=1500000 textures=300 seed=1 texture_size=512
repeats=3 width=512 height=256 spp=16 variants=instance
usage() { sed -n '2,27p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case $1 in --help | -h) usage; exit 0 ;; esac
  [ $# -ge 2 ] || { echo "bench_scale: $1 needs a value (see --help)" >&2; exit 2; }
  case $1 in
    --phyir) phyir=$2 ;;
    --out) out=$2 ;;
    --scene-dir) scene_dir=$2 ;;
    --triangles) triangles=$2 ;;
    --textures) textures=$2 ;;
    --seed) seed=$2 ;;
    --texture-size) texture_size=$2 ;;
    --repeats) repeats=$2 ;;
    --width) width=$2 ;;
    --height) height=$2 ;;
    --spp) spp=$2 ;;
    --variants) variants=$2 ;;
    *) echo "bench_scale: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
[ -x "$phyir" ] || { echo "bench_scale: '$phyir' is not an executable (--phyir)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_scale: /usr/bin/time not found (apt-get install time)" >&2; exit 2; }
phyir=$(realpath "$phyir")
mkdir -p "$out"
out=$(realpath "$out")
scene_dir=$(realpath -m "${scene_dir:-$out/big_room}")

# The scenes.
big=$scene_dir/big_room.gltf
if [ ! -f "$big" ]; then
  command -v blender >/dev/null || { echo "bench_scale: blender not found and $big absent" >&2; exit 1; }
  echo "bench_scale: generating $big with Blender (about a minute)" >&2
  blender -b --factory-startup --python-exit-code 1 --python "$root/scripts/blender/make_big_room.py" -- \
    --out "$scene_dir" --triangles "$triangles" --textures "$textures" --seed "$seed" \
    --texture-size "$texture_size" >"$out/make_big_room.log" 2>&1 ||
    { tail -20 "$out/make_big_room.log" >&2; echo "bench_scale: make_big_room.py failed" >&2; exit 1; }
fi
scenes=("big_room=$big")
if [ "$variants" != none ]; then
  if [ ! -f "$scene_dir/variants/instance.gltf" ]; then
    "$root/scripts/gltf_variants.sh" "$big" "$scene_dir/variants" >"$out/gltf_variants.log" 2>&1 ||
      { tail -20 "$out/gltf_variants.log" >&2; echo "bench_scale: gltf_variants.sh failed" >&2; exit 1; }
  fi
  IFS=, read -r -a names <<<"$variants"
  for name in "${names[@]}"; do scenes+=("big_room_$name=$scene_dir/variants/$name.gltf"); done
fi
"$phyir" --log-level warn scenes generate --out "$out/mini" --preset mini --seed 1 >/dev/null
scenes+=("lit_room=$root/tests/data/gltf/blender_lit_room/lit_room.gltf" "mini_room=$out/mini/room_0.gltf")

# The runs: every measurement of every scene, then again, so load changes hit all scenes alike.
runs=$out/runs.csv
echo "scene,repeat,what,load1_before,wall_seconds,max_rss_kb,result" >"$runs"
timed() {  # NAME REPEAT WHAT RESULT_FILE COMMAND...: runs COMMAND under /usr/bin/time -v
  local name=$1 repeat=$2 what=$3 result=$4
  shift 4
  local load1 log=$out/runs/$name.$what.$repeat.time
  load1=$(cut -d' ' -f1 /proc/loadavg)
  if ! /usr/bin/time -v -o "$log" "$@" >"$out/runs/$name.$what.$repeat.log" 2>&1; then
    tail -5 "$out/runs/$name.$what.$repeat.log" >&2
    echo "bench_scale: $what of $name failed" >&2
    exit 1
  fi
  local wall rss
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s }' "$log")
  rss=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$log")
  echo "$name,$repeat,$what,$load1,$wall,$rss,$result" >>"$runs"
  echo "bench_scale: $name $what run $repeat: ${wall} s, $((rss / 1024)) MiB peak, load $load1" >&2
}
mkdir -p "$out/runs"
for repeat in $(seq 1 "$repeats"); do
  for entry in "${scenes[@]}"; do
    name=${entry%%=*} file=${entry#*=}
    [ -f "$file" ] || { echo "bench_scale: $file not found" >&2; exit 1; }
    timed "$name" "$repeat" info "$out/runs/$name.info.$repeat.json" \
      sh -c '"$1" --log-level warn scenes info --json "$2" >"$3"' sh "$phyir" "$file" "$out/runs/$name.info.$repeat.json"
    rdir=$out/runs/$name.render.$repeat
    timed "$name" "$repeat" render "$rdir/render.json" \
      "$phyir" --log-level warn render "$file" --out "$rdir" --width "$width" --height "$height" --spp "$spp" --quiet --no-aovs
    tdir=$out/runs/$name.throughput.$repeat
    timed "$name" "$repeat" throughput "$tdir/throughput.json" \
      "$phyir" --log-level warn bench throughput "$file" --out "$tdir"
  done
done

/usr/bin/python3 - "$out" "$width" "$height" "$spp" <<'EOF'
import csv, json, os, platform, sys
out, width, height, spp = sys.argv[1], *map(int, sys.argv[2:5])
runs = list(csv.DictReader(open(os.path.join(out, "runs.csv"))))
scenes = list(dict.fromkeys(r["scene"] for r in runs))
def float_pyramid_bytes(t):  # binaries before `bytes` kept float RGBA, mips halved down to 1x1
    w, h, total = t["width"], t["height"], 0
    while w * h > 0:
        total += w * h * 16
        if w == 1 and h == 1:
            break
        w, h = max(1, (w + 1) // 2), max(1, (h + 1) // 2)
    return total
rows = []
for scene in scenes:
    mine = [r for r in runs if r["scene"] == scene]
    pick = lambda what: [r for r in mine if r["what"] == what]
    info = json.load(open(pick("info")[0]["result"]))
    renders = [json.load(open(r["result"])) for r in pick("render")]
    throughputs = [json.load(open(r["result"])) for r in pick("throughput")]
    texture_bytes = sum(t["bytes"] if "bytes" in t else float_pyramid_bytes(t) for t in info["textures"])
    rows.append({
        "scene": scene,
        "file": info["source"],
        "triangles": info["triangles"],
        "unique_triangles": info["source_info"]["unique_triangles"],
        "vertices": info["vertices"],
        "meshes": info["meshes"],
        "textures": len(info["textures"]),
        "texture_mib": round(texture_bytes / 2**20, 1),
        "info_seconds": min(float(r["wall_seconds"]) for r in pick("info")),
        "info_peak_rss_mib": round(min(int(r["max_rss_kb"]) for r in pick("info")) / 1024, 1),
        "load_seconds": round(min(j["timings"]["load_seconds"] for j in renders), 3),
        "build_seconds": round(min(j["timings"]["build_seconds"] for j in renders), 3),
        "render_color_seconds": round(min(j["timings"]["color_seconds"] for j in renders), 2),
        "render_peak_rss_mib": round(min(int(r["max_rss_kb"]) for r in pick("render")) / 1024, 1),
        "render_rays_per_second": round(max(j["counters"]["rays_per_second"] for j in renders)),
        "bench_integrator_rays_per_second": round(max(j["integrator_rays_per_second"] for j in throughputs)),
        "bench_embree_single_rays_per_second": round(max(j["embree_single_rays_per_second"] for j in throughputs)),
        "bench_embree_packet_rays_per_second": round(max(j["embree_packet_rays_per_second"] for j in throughputs)),
        "load1_min": min(float(r["load1_before"]) for r in mine),
        "load1_max": max(float(r["load1_before"]) for r in mine),
        "repeats": len(renders),
    })
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.processor())
machine = {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30, 1),
           "phyir_machine": json.load(open([r for r in runs if r["what"] == "throughput"][0]["result"]))["machine"]}
method = (f"minimum over {rows[0]['repeats']} interleaved runs of times and peak RSS, maximum of rays/s; render {width}x{height} "
          f"equirect {spp} spp, 8 bounces; bench throughput 256x128 16 spp; load1 = 1-minute load average before each run")
json.dump({"machine": machine, "method": method, "scenes": rows}, open(os.path.join(out, "scale.json"), "w"), indent=2)
with open(os.path.join(out, "scale.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
m = lambda x: f"{x / 1e6:.2f} M"
lines = ["| scene | triangles | unique | textures | texture memory | load s | BVH build s | peak RSS (info / render) | rays/s bench | rays/s render | Embree single | load avg |",
         "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
for r in rows:
    lines.append(f"| {r['scene']} | {r['triangles']:,} | {r['unique_triangles']:,} | {r['textures']} | {r['texture_mib']} MiB | "
                 f"{r['load_seconds']:.2f} | {r['build_seconds']:.2f} | {r['info_peak_rss_mib']:.0f} / {r['render_peak_rss_mib']:.0f} MiB | "
                 f"{m(r['bench_integrator_rays_per_second'])} | {m(r['render_rays_per_second'])} | "
                 f"{m(r['bench_embree_single_rays_per_second'])} | {r['load1_min']:.1f}-{r['load1_max']:.1f} |")
lines += ["", f"Machine: {machine['cpu']}, {machine['cores']} cores, {machine['memory_gib']} GiB. {method}."]
open(os.path.join(out, "scale.md"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
