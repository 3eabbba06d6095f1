# Shared by compare.sh and compare_furnished.sh (sourced, not run): the render steps of the
# phyir / Cycles comparison. Method: docs/cycles-comparison.md.
#
# Expects ROOT, PHYIR, BLENDER and the globals scene, width, height, camera, threads;
# defines ours_bounces / cycles_bounces. Every render is skipped when its output exists, so
# an interrupted run resumes. Run the caller under `nice` on a shared machine: the renders
# inherit it.

# Cycles: `max_bounces = B` renders our `--max-bounces B + 1` (it counts bounces after the
# first hit); ours is 8, Russian roulette from bounce 3.
ours_bounces=8
cycles_bounces=$((ours_bounces - 1))

# Wall and CPU seconds of a whole process into OUT (JSON), and the load average at its
# start into OUT with .load instead of .time.json.
timed() {
  local out="$1"; shift
  cut -d' ' -f1-3 /proc/loadavg >"${out%.time.json}.load"
  /usr/bin/time -f '{"wall_seconds": %e, "user_seconds": %U, "system_seconds": %S}' -o "$out" "$@"
}

render_ours() {  # DIR SPP SEED [extra flags]
  local dir="$1" spp="$2" seed="$3"; shift 3
  [[ -f "$dir/render.json" ]] && return 0
  timed "$dir.time.json" "$PHYIR" render "$scene" --out "$dir" --width "$width" --height "$height" \
    --spp "$spp" --seed "$seed" --camera="$camera" --max-bounces "$ours_bounces" --threads "$threads" --quiet "$@" >/dev/null
}

render_cycles() {  # OUT.exr SPP SEED MODE [extra flags]
  local out="$1" spp="$2" seed="$3" mode="$4"; shift 4
  [[ -f "${out%.exr}.json" ]] && return 0
  timed "${out%.exr}.time.json" "$BLENDER" -b --factory-startup -noaudio -t "$threads" \
    --python "$ROOT/scripts/cycles/render_cycles.py" -- --gltf "$scene" --out "$out" \
    --width "$width" --height "$height" --samples "$spp" --seed "$seed" --bounces "$cycles_bounces" \
    --camera="$camera" --threads "$threads" --materials "$mode" "$@" >"${out%.exr}.log" 2>&1 ||
    { echo "$(basename "$0"): Cycles failed, see ${out%.exr}.log" >&2; tail -20 "${out%.exr}.log" >&2; exit 1; }
}

# The machine, the binaries and the settings, for the figures' captions and the docs.
write_machine() {  # OUT.txt, then lines to append on standard input
  {
    echo "date: $(date -Iseconds)"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) cores"
    echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "phyir: $PHYIR ($("$PHYIR" --version 2>/dev/null | head -1), built $(date -r "$PHYIR" -Iseconds), md5 $(md5sum "$PHYIR" | cut -c1-12)); scripts from $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "blender: $("$BLENDER" --version 2>/dev/null | head -1)"
    echo "threads: $threads; ours --max-bounces $ours_bounces, Cycles max_bounces $cycles_bounces; niceness $(nice)"
    cat
  } >"$1"
}
