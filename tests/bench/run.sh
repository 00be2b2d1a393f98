#!/usr/bin/env bash
# modelc benchmarks (make bench): writes tests/bench/RESULTS.md.
#
# For the default model baked at several depths, at one screen size, a full turn of views:
#   1. size (budget.json) and speed (the viewer's --bench, with and without finishing)
#   2. instructions per drawn point of mc_octree_render under callgrind (tests/bench/callgrind_frames.c)
#   3. the same cells drawn by Mesa's software OpenGL, single-threaded llvmpipe via OSMesa
#      (tests/bench/osmesa_points.c), timed interleaved with modelc
#   4. the same cells' geometry compressed by Draco
# Everything goes under build/bench/; the raw outputs stay in build/bench/results/.
#
# Settings (environment): MODELC (generator, default build/bin/modelc), BENCH_MODEL (catalogue name,
# default bunny00), BENCH_DEPTHS ("6 7 8 9"), BENCH_FRAMES (200), BENCH_ROUNDS (5), CG_FRAMES (20),
# BENCH_SIZE (320x240), CC (gcc).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD

MODELC=${MODELC:-build/bin/modelc}
MODEL=${BENCH_MODEL:-bunny00}
DEPTHS=${BENCH_DEPTHS:-6 7 8 9}
FRAMES=${BENCH_FRAMES:-200}
ROUNDS=${BENCH_ROUNDS:-5}
CG_FRAMES=${CG_FRAMES:-20}
SIZE=${BENCH_SIZE:-320x240}
. tests/bench/common.sh   # CC, OPT, RT_FLAGS, HOST_FLAGS, bench_quote

OUT=build/bench
RES=$OUT/results
SNAP=$OUT/src/runtime
OBJ=$OUT/obj
T0=$(date +%s)

die() { echo "bench: $*" >&2; exit 1; }
# every command that matters goes through run: logged (shell-quoted) for RESULTS.md, then executed
run() {
    printf '%s\n' "$(bench_quote "$@")" >>"$RES/commands.log"
    "$@"
}
step() { printf '[bench %4ss] %s\n' "$(($(date +%s) - T0))" "$*"; }

# ---- prerequisites --------------------------------------------------------------------------------
src_model=$(make -s --no-print-directory -f - print <<EOF 2>/dev/null || true
include models/catalogue.mk
print: ; @echo \$(notdir \$($MODEL.src))
EOF
)
[ -n "$src_model" ] || die "model $MODEL is not in models/catalogue.mk"
MODEL_FILE=build/models/$src_model
[ -f "$MODEL_FILE" ] || die "$MODEL_FILE missing: run make models"
[ -x "$MODELC" ] || die "$MODELC missing: run make gen (or set MODELC=path/to/modelc)"
for tool in valgrind callgrind_annotate draco_encoder draco_decoder python3 "$CC"; do
    command -v "$tool" >/dev/null || die "$tool not found: run make deps"
done
[ -f /usr/include/GL/osmesa.h ] || die "GL/osmesa.h missing: run make deps (libosmesa6-dev)"

rm -rf "$RES" "$OUT/src" "$OBJ"
mkdir -p "$RES" "$SNAP" "$OBJ/rt" "$OBJ/host" "$OUT/bin"
: >"$RES/commands.log"

# ---- the machine ----------------------------------------------------------------------------------
pkgver() { dpkg-query -W -f='${Package} ${Version}' "$1" 2>/dev/null || echo "$1 ?"; }
{
    echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
    echo "nproc: $(nproc)"
    echo "mem: $(awk '/MemTotal/ {printf "%.1f GiB RAM", $2 / 1048576}' /proc/meminfo)"
    echo "kernel: $(uname -srm)"
    echo "load_start: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "cc_version: $($CC --version | head -n1)"
    echo "valgrind: $(valgrind --version)"
    echo "mesa_pkg: $(pkgver libosmesa6), $(pkgver libgl1-mesa-dri)"
    echo "draco_pkg: $(pkgver draco)"
    echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
    if [ -z "$(git status --porcelain -- runtime 2>/dev/null)" ]; then
        echo "runtime_state: as committed"
    else
        echo "runtime_state: with uncommitted changes ($(git status --porcelain -- runtime | wc -l) files)"
    fi
    echo "snapshot: $SNAP"
    echo "modelc: $MODELC"
    echo "modelc_version: $("$MODELC" --version 2>/dev/null | head -n1 || echo '?')"
    echo "model_src: $MODEL_FILE"
    echo "depths: $DEPTHS"
    echo "frames: $FRAMES"
    echo "rounds: $ROUNDS"
    echo "cg_frames: $CG_FRAMES"
    echo "size: $SIZE"
    echo "target_depth: 8"
    echo "rot_yaw: $((4096 * 3 / 20))"
} >"$RES/meta.txt"

# ---- runtime: a snapshot, so that timings, callgrind and its annotations all see the same code -----
step "runtime snapshot and objects"
cp -r runtime/include runtime/src runtime/front "$SNAP/"
echo "render_sha: $(sha256sum "$SNAP/src/octree_render.c" | cut -c1-16)" >>"$RES/meta.txt"
INC="-I$SNAP/include -I$SNAP/front/host"
for f in "$SNAP"/src/*.c; do
    run $CC $OPT $RT_FLAGS $INC -c -o "$OBJ/rt/$(basename "${f%.c}").o" "$f"
done
for f in "$SNAP"/front/host/*.c "$SNAP"/front/common/*.c; do
    run $CC $OPT $HOST_FLAGS $INC -c -o "$OBJ/host/$(basename "${f%.c}").o" "$f"
done

# ---- bakes and binaries -----------------------------------------------------------------------------
for d in $DEPTHS; do
    name=${MODEL}_d$d
    step "depth $d: bake $name and build its viewer, callgrind driver and OSMesa driver"
    rm -rf "$OUT/$name"
    t=$(date +%s.%N)
    run "$MODELC" "$MODEL_FILE" -o "$OUT" --name "$name" --depth "$d" --quiet >"$RES/d$d.bake.log" 2>&1 ||
        { cat "$RES/d$d.bake.log"; die "bake at depth $d failed"; }
    awk -v a="$t" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f\n", b - a }' >"$RES/d$d.bake.seconds"
    cp "$OUT/$name/budget.json" "$RES/d$d.budget.json"
    mkdir -p "$OBJ/$name"
    for f in "$OUT/$name"/*.c; do
        run $CC $OPT $RT_FLAGS $INC -ffunction-sections -fdata-sections -c -o "$OBJ/$name/$(basename "${f%.c}").o" "$f"
    done
    run $CC $OPT $RT_FLAGS -o "$OUT/bin/$name-view" "$OBJ/$name"/*.o "$OBJ"/rt/*.o "$OBJ"/host/*.o \
        -Wl,--gc-sections -lm
    run $CC $OPT $HOST_FLAGS $INC -o "$OUT/bin/$name-callgrind" tests/bench/callgrind_frames.c "$OBJ/$name"/*.o \
        "$OBJ"/rt/*.o -Wl,--gc-sections
    run $CC $OPT $HOST_FLAGS $INC -o "$OUT/bin/$name-osmesa" tests/bench/osmesa_points.c "$OBJ/$name"/*.o \
        -Wl,--gc-sections -lOSMesa -lm
done

# ---- 2. callgrind -----------------------------------------------------------------------------------
CG_OPTS=(--tool=callgrind --toggle-collect=mc_octree_render --branch-sim=yes --compress-strings=no --compress-pos=no)
for d in $DEPTHS; do
    name=${MODEL}_d$d
    step "depth $d: callgrind ($CG_FRAMES-view turn and frontal)"
    run valgrind "${CG_OPTS[@]}" --callgrind-out-file="$RES/d$d.cg.turn.out" "$OUT/bin/$name-callgrind" \
        "$CG_FRAMES" --size "$SIZE" >"$RES/d$d.cg.turn.txt" 2>"$RES/d$d.cg.turn.log"
    run valgrind "${CG_OPTS[@]}" --callgrind-out-file="$RES/d$d.cg.front.out" "$OUT/bin/$name-callgrind" \
        1 --size "$SIZE" >"$RES/d$d.cg.front.txt" 2>"$RES/d$d.cg.front.log"
    for v in turn front; do
        python3 tests/bench/bench_tools.py cg-total "$RES/d$d.cg.$v.out" >"$RES/d$d.cg.$v.total"
    done
    python3 tests/bench/bench_tools.py cg-lines "$RES/d$d.cg.turn.out" "$SNAP" 20 >"$RES/d$d.cg.lines.md"
    run callgrind_annotate --auto=yes --inclusive=no "$RES/d$d.cg.turn.out" >"$RES/d$d.cg.annotate.txt" 2>&1 || true
done

d_first=${DEPTHS%% *}
run valgrind --tool=callgrind --toggle-collect=mc_clear --callgrind-out-file="$RES/clear.cg.out" \
    "$OUT/bin/${MODEL}_d$d_first-callgrind" 1 --size "$SIZE" >/dev/null 2>"$RES/clear.cg.log"
python3 tests/bench/bench_tools.py cg-total "$RES/clear.cg.out" >"$RES/clear.cg.total"

# ---- 3 (check). same pixels: modelc's and Mesa's frames side by side, untimed ------------------------
ROT_YAW=$((4096 * 3 / 20))    # a rotated view: frame 3 of a 20-frame turn, about 54 degrees
for d in $DEPTHS; do
    name=${MODEL}_d$d
    step "depth $d: pixel coverage and images (frontal, yaw $ROT_YAW units), modelc vs Mesa"
    run "$OUT/bin/$name-callgrind" "$CG_FRAMES" --size "$SIZE" --ppm "$RES/d$d.modelc.front.ppm" \
        --mask "$RES/d$d.modelc.front.pgm" >"$RES/d$d.pixels.modelc.txt"
    run env LP_NUM_THREADS=0 "$OUT/bin/$name-osmesa" --no-bench --views "$CG_FRAMES" --size "$SIZE" \
        --ppm "$RES/d$d.mesa.front.ppm" --mask "$RES/d$d.mesa.front.pgm" >"$RES/d$d.pixels.mesa.txt"
    run "$OUT/bin/$name-callgrind" 1 --size "$SIZE" --image-yaw "$ROT_YAW" --ppm "$RES/d$d.modelc.rot.ppm" \
        --mask "$RES/d$d.modelc.rot.pgm" >"$RES/d$d.pixels.modelc.rot.txt"
    run env LP_NUM_THREADS=0 "$OUT/bin/$name-osmesa" --no-bench --views 0 --size "$SIZE" --image-yaw "$ROT_YAW" \
        --ppm "$RES/d$d.mesa.rot.ppm" --mask "$RES/d$d.mesa.rot.pgm" >"$RES/d$d.pixels.mesa.rot.txt"
    for v in front rot; do
        python3 tests/bench/bench_tools.py image-cmp "$RES/d$d.modelc.$v.ppm" "$RES/d$d.mesa.$v.ppm" \
            "$RES/d$d.modelc.$v.pgm" "$RES/d$d.mesa.$v.pgm" >"$RES/d$d.image.$v.cmp"
    done
done

# ---- 1 + 3. timings, interleaved ------------------------------------------------------------------
# Each round is A-B-A: modelc (without and with finishing), Mesa, modelc again; a round's modelc time is
# the mean of its two runs, so that modelc and Mesa see the same machine load (other processes share it).
# modelc is timed by the viewer's --bench (wall clock) and by callgrind_frames --time (the same loop,
# wall clock and process CPU time); Mesa reports both clocks too. On a busy machine a 30 ms Mesa frame
# is far more often preempted than a 1 ms modelc frame, so the CPU-time ratio is the fair one there.
for d in $DEPTHS; do
    name=${MODEL}_d$d
    for r in $(seq 1 "$ROUNDS"); do
        step "depth $d: timing round $r/$ROUNDS (modelc, Mesa, modelc)"
        cut -d' ' -f1 /proc/loadavg >>"$RES/load.txt"
        for ab in a mesa b; do
            if [ "$ab" = mesa ]; then
                run env LP_NUM_THREADS=0 "$OUT/bin/$name-osmesa" --frames "$FRAMES" --views 0 --size "$SIZE" \
                    >"$RES/d$d.mesa.r$r.txt"
            else
                run "$OUT/bin/$name-view" --bench "$FRAMES" --size "$SIZE" --no-finish >"$RES/d$d.nofinish.r$r.$ab.txt"
                run "$OUT/bin/$name-view" --bench "$FRAMES" --size "$SIZE" >"$RES/d$d.finish.r$r.$ab.txt"
                run "$OUT/bin/$name-callgrind" --time "$FRAMES" --size "$SIZE" >"$RES/d$d.cpu.nofinish.r$r.$ab.txt"
                run "$OUT/bin/$name-callgrind" --time "$FRAMES" --finish --size "$SIZE" >"$RES/d$d.cpu.finish.r$r.$ab.txt"
            fi
        done
    done
done
cut -d' ' -f1 /proc/loadavg >>"$RES/load.txt"

# ---- 4. Draco ---------------------------------------------------------------------------------------
for d in $DEPTHS; do
    name=${MODEL}_d$d
    step "depth $d: Draco"
    run "$OUT/bin/$name-osmesa" --no-bench --views 0 --ply "$OUT/$name/cells.ply" --ply-rgb "$OUT/$name/cells_rgb.ply"
    run draco_encoder -point_cloud -i "$OUT/$name/cells.ply" -o "$OUT/$name/cells.cl7.drc" -qp "$d" >"$RES/d$d.draco.cl7.log"
    run draco_encoder -point_cloud -i "$OUT/$name/cells.ply" -o "$OUT/$name/cells.cl10.drc" -qp "$d" -cl 10 >"$RES/d$d.draco.cl10.log"
    run draco_encoder -point_cloud -i "$OUT/$name/cells_rgb.ply" -o "$OUT/$name/cells_rgb.cl10.drc" -qp "$d" -cl 10 \
        >"$RES/d$d.draco.rgb.cl10.log"
    stat -c %s "$OUT/$name/cells.cl7.drc" >"$RES/d$d.draco.cl7.bytes"
    stat -c %s "$OUT/$name/cells.cl10.drc" >"$RES/d$d.draco.cl10.bytes"
    stat -c %s "$OUT/$name/cells_rgb.cl10.drc" >"$RES/d$d.draco.rgb.cl10.bytes"
    run draco_decoder -i "$OUT/$name/cells.cl10.drc" -o "$OUT/$name/cells.decoded.ply" >/dev/null
    python3 tests/bench/bench_tools.py ply-check "$OUT/$name/cells.ply" "$OUT/$name/cells.decoded.ply" \
        >"$RES/d$d.draco.check"
    rm -f "$OUT/$name/cells_rgb.ply" "$OUT/$name/cells.decoded.ply"
done

# ---- report -----------------------------------------------------------------------------------------
echo "load_end: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$RES/meta.txt"
python3 tests/bench/bench_tools.py report "$RES" tests/bench/RESULTS.md
step "interaction timing and hole filling: sections appended to tests/bench/RESULTS.md"
INTERACTION_RUNTIME=$SNAP tests/bench/interaction.sh tests/bench/RESULTS.md >"$RES/interaction.md"
tests/bench/holes.sh tests/bench/RESULTS.md >"$RES/holes.log" || true
step "depth test as a branch and as a select, side by side with Mesa: section appended"
tests/bench/depth_select.sh tests/bench/RESULTS.md "$SNAP" >"$RES/select.log"
step "squares walked by a loop per node and by a mask: section appended"
tests/bench/flat_squares.sh tests/bench/RESULTS.md >"$RES/flat.log"
step "the progressive mesh against OpenMesh: section appended"
tests/bench/pmesh.sh tests/bench/RESULTS.md >"$RES/pmesh.log"
step "filled triangles and line drawings against Mesa's llvmpipe: section appended"
tests/bench/mesh.sh tests/bench/RESULTS.md >"$RES/mesh.log"
step "silhouettes, searched against the exact scan: section appended"
tests/bench/silhouette.sh tests/bench/RESULTS.md >"$RES/silhouette.log"
step "the tracker's particle filter on a synthetic cube sequence: section appended"
tests/bench/track.sh tests/bench/RESULTS.md >"$RES/track.log"
step "the tracker on real and synthetic sequences beside ViSP (make deps-bench): section appended"
tests/bench/track_seq.sh tests/bench/RESULTS.md >"$RES/track_seq.log"
step "level of detail, run time against error: section appended"
tests/bench/lod_error.sh tests/bench/RESULTS.md >"$RES/lod_error.log"
step "the automatic level of detail against frame-time targets: section appended"
tests/bench/lod_auto.sh tests/bench/RESULTS.md >"$RES/lod_auto.log"
step "the level of detail's neighbour table in line drawings: section appended"
tests/bench/neighbours.sh tests/bench/RESULTS.md >"$RES/neighbours.log"
step "face groups' normal cones, what a hierarchy could spare the line drawings: section appended"
tests/bench/cone_groups.sh tests/bench/RESULTS.md >"$RES/cone_groups.log"
step "wrote tests/bench/RESULTS.md"
sed -n '/^## Summary/,/^## Commands/p' tests/bench/RESULTS.md | sed '$d'
