#!/usr/bin/env bash
# make bench-views: the point renderer at every view, with its screen-space level of detail on and off,
# side by side with Mesa llvmpipe on one thread in the same run: what each view costs against what its
# pixels need. Writes the "views" section of tests/bench/RESULTS.md (or of the file given as
# $1) through tests/bench/section.sh.
#
# bunny00 baked at depths 8, 9 and 10 (build/bench/views/bNN, as `modelc MODEL -o build/bench/views
# --name bNN --depth D -q`, plus --dump-reference for the mesh reference; by a copy of build/bin/modelc
# taken at the start, as the runtime is, so that a rebuild meanwhile cannot split the run). Rows: 320x240 zoom 1
# orthographic (the benchmark), zoom 0.25, 640x480 zoom 1, perspective (eye 2 cube sides) at 320x240
# and 640x480, all on the depth-8 bake; 320x240 zoom 1 on the depth-9 and depth-10 bakes. Each row is
# drawn with the level of detail on (--error 1: max_error one pixel, the viewer's default) and off
# (--error 0: the bake's depth), and for each:
#   - instructions: callgrind, only mc_octree_render collected (tests/bench/callgrind_frames.c, a turn
#     of CG_FRAMES views); per frame, and per drawn leaf (mc_stats.points); the level drawn (mc_stats.depth),
#     checked against what the viewer's --bench prints for the same view;
#   - time: callgrind_frames --time (mc_clear + mc_octree_render, no finishing) and Mesa
#     (tests/bench/osmesa_points.c --footprint: every leaf of the bake, the same projection, points as
#     large as modelc's footprint of a leaf), LP_NUM_THREADS=0, interleaved A-B-A in ROUNDS rounds;
#   - coverage: mean pixels covered, modelc (level of detail off) against Mesa, and the frontal images;
#   - image quality (depth rows): PSNR against the double-precision mesh reference (runtime/ref/mesh_ref.c)
#     of the viewer's frame (tests/bench/views_psnr.c: mc_host_scene_draw, default footprint and fill).
# Everything lives under build/bench/views/; raw outputs in build/bench/views/res/.
#
# Settings (environment): MODELC (build/bin/modelc), VIEWS_DEPTHS ("8 9 10"), VIEWS_FRAMES (40: frames of
# the timed turn; Mesa needs about a second a frame at depth 10), VIEWS_ROUNDS (3), CG_FRAMES (20),
# VIEWS_PSNR_VIEWS (8), VIEWS_BAKE_TIMEOUT (600 s per bake), CC (gcc).
set -u -o pipefail
cd "$(dirname "$0")/../.." || exit 1
. tests/lib.sh            # runtime_snapshot, model_file
. tests/bench/section.sh  # write_section

results=${1:-tests/bench/RESULTS.md}
MODELC=${MODELC:-build/bin/modelc}
DEPTHS=${VIEWS_DEPTHS:-8 9 10}
FRAMES=${VIEWS_FRAMES:-40}
ROUNDS=${VIEWS_ROUNDS:-3}
CG_FRAMES=${CG_FRAMES:-20}
PSNR_VIEWS=${VIEWS_PSNR_VIEWS:-8}
BAKE_TIMEOUT=${VIEWS_BAKE_TIMEOUT:-600}
. tests/bench/common.sh   # CC, OPT, RT_FLAGS, HOST_FLAGS, bench_quote
OUT=build/bench/views
RES=$OUT/res
OBJ=$OUT/obj
BIN=$OUT/bin
T0=$(date +%s)

die() { echo "bench-views: $*" >&2; exit 1; }
step() { printf '[bench-views %4ss] %s\n' "$(($(date +%s) - T0))" "$*"; }
# every command that makes a figure goes through run: logged for the section, then executed; a failure
# stops the benchmark with one line (the command's own output is in the file it was sent to)
run() {
    local q
    q=$(bench_quote "$@")
    printf '%s\n' "$q" >>"$RES/commands.log"
    "$@" || die "failed (status $?): $q"
}
# compile_each OBJDIR 'GLOB' COMPILER FLAGS...: every file of GLOB compiled into OBJDIR/NAME.o, logged as
# the one shell loop it is (a depth-10 bake has dozens of data files)
compile_each() {
    local dir=$1 glob=$2 f
    shift 2
    printf 'for f in %s; do %s -c -o %s/$(basename "${f%%.c}").o "$f"; done\n' "$glob" "$*" "$dir" >>"$RES/commands.log"
    for f in $glob; do
        "$@" -c -o "$dir/$(basename "${f%.c}").o" "$f" || die "failed: $* -c -o $dir/$(basename "${f%.c}").o $f"
    done
}

# ---- prerequisites ----------------------------------------------------------------------------------
for tool in valgrind python3 "$CC"; do
    command -v "$tool" >/dev/null || die "$tool not found: run make deps"
done
[ -f /usr/include/GL/osmesa.h ] || die "GL/osmesa.h missing: run make deps (libosmesa6-dev)"
[ -x "$MODELC" ] || die "$MODELC missing: run make gen (or set MODELC=path/to/modelc)"
MODEL_FILE=$(model_file bunny00) || die "bunny00 missing: run make models"
if ! [ "$ROUNDS" -ge 1 ] 2>/dev/null || ! [ "$FRAMES" -ge 1 ] 2>/dev/null || ! [ "$CG_FRAMES" -ge 1 ] 2>/dev/null; then
    die "VIEWS_ROUNDS, VIEWS_FRAMES and CG_FRAMES must be integers >= 1"
fi

rm -rf "$RES" "$OBJ" "$BIN" "$OUT/src"
mkdir -p "$RES" "$OBJ/rt" "$OBJ/host" "$OBJ/ref" "$BIN"
: >"$RES/commands.log"

# ---- runtime: a snapshot (others edit runtime/ meanwhile), so every binary of the run has the same code --
step "runtime snapshot and objects"
runtime_snapshot "$OUT/src" >"$RES/runtime_source.txt" || die "cannot copy the runtime"
cp -r runtime/ref "$OUT/src/runtime/" || die "cannot copy runtime/ref"
SNAP=$OUT/src/runtime
INC="-I$SNAP/include -I$SNAP/front/host -I$SNAP/ref"
compile_each "$OBJ/rt" "$SNAP/src/*.c" $CC $OPT $RT_FLAGS $INC
compile_each "$OBJ/host" "$SNAP/front/host/*.c $SNAP/front/common/*.c" $CC $OPT $HOST_FLAGS $INC
# the mesh reference, and ref.c for the rotation it shares
compile_each "$OBJ/ref" "$SNAP/ref/ref.c $SNAP/ref/mesh_ref.c" $CC $OPT $HOST_FLAGS $INC

# ---- the generator: a copy too (others rebuild build/bin/modelc meanwhile), so every bake has the same one --
step "generator snapshot"
GEN=$BIN/modelc
for try in 1 2 3; do
    cp "$MODELC" "$GEN" 2>/dev/null && "$GEN" --version >/dev/null 2>&1 && break
    [ "$try" = 3 ] && die "$MODELC does not run (being rebuilt?): try again when make gen is done"
    sleep 10
done
echo "$MODELC, sha256 $(sha256sum "$GEN" | cut -c1-16)" >"$RES/generator.txt"

# ---- bakes and their programs ------------------------------------------------------------------------
# A bake that fails or overruns VIEWS_BAKE_TIMEOUT is recorded (res/bake.D.status) and its rows reported
# as not measured, rather than dropped.
TIME_CMD=()
[ -x /usr/bin/time ] && TIME_CMD=(/usr/bin/time -f "%e %M" -o)
baked=""
for d in $DEPTHS; do
    name=$(printf 'b%02d' "$d")
    step "depth $d: bake $name, build its viewer, callgrind driver, OSMesa driver and PSNR program"
    rm -rf "${OUT:?}/$name"
    t=$(date +%s.%N)
    cmd=("$GEN" "$MODEL_FILE" -o "$OUT" --name "$name" --depth "$d" -q --dump-reference "$RES/$name.ref")
    printf '%s\n' "${cmd[*]}" >>"$RES/commands.log"
    if [ ${#TIME_CMD[@]} -gt 0 ]; then
        timeout "$BAKE_TIMEOUT" "${TIME_CMD[@]}" "$RES/bake.$d.time" "${cmd[@]}" >"$RES/bake.$d.log" 2>&1
    else
        timeout "$BAKE_TIMEOUT" "${cmd[@]}" >"$RES/bake.$d.log" 2>&1
    fi
    rc=$?
    awk -v a="$t" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f\n", b - a }' >"$RES/bake.$d.seconds"
    if [ "$rc" -eq 124 ]; then
        echo "not baked: modelc ran over the ${BAKE_TIMEOUT} s limit (VIEWS_BAKE_TIMEOUT)" >"$RES/bake.$d.status"
        step "depth $d: bake timed out, its rows are reported as not measured"
        continue
    elif [ "$rc" -ne 0 ] || [ ! -f "$OUT/$name/budget.json" ]; then
        echo "not baked: modelc exited with status $rc: $(grep -v '^Command exited' "$RES/bake.$d.log" | tail -n 2 | tr '\n' ' ')" \
            >"$RES/bake.$d.status"
        step "depth $d: bake failed, its rows are reported as not measured"
        continue
    fi
    echo ok >"$RES/bake.$d.status"
    cp "$OUT/$name/budget.json" "$RES/$name.budget.json"
    mkdir -p "$OBJ/$name"
    compile_each "$OBJ/$name" "$OUT/$name/*.c" $CC $OPT $RT_FLAGS $INC -ffunction-sections -fdata-sections
    run $CC $OPT $RT_FLAGS -o "$BIN/$name-view" "$OBJ/$name"/*.o "$OBJ"/rt/*.o "$OBJ"/host/*.o -Wl,--gc-sections -lm
    run $CC $OPT $HOST_FLAGS $INC -o "$BIN/$name-frames" tests/bench/callgrind_frames.c "$OBJ/$name"/*.o "$OBJ"/rt/*.o \
        -Wl,--gc-sections
    run $CC $OPT $HOST_FLAGS $INC -o "$BIN/$name-osmesa" tests/bench/osmesa_points.c "$OBJ/$name"/*.o -Wl,--gc-sections \
        -lOSMesa -lm
    run $CC $OPT $HOST_FLAGS $INC -o "$BIN/$name-psnr" tests/bench/views_psnr.c "$OBJ/$name"/*.o "$OBJ/host/scene.o" \
        "$OBJ/host/mesh_frame.o" "$OBJ"/ref/*.o "$OBJ"/rt/*.o -Wl,--gc-sections -lm
    baked+=" $d"
done

# ---- the rows: key, size, zoom, projection, bake depth ---------------------------------------------------
ROWS=(
    "bench 320x240 1 ortho 8"
    "quarter 320x240 0.25 ortho 8"
    "big 640x480 1 ortho 8"
    "persp 320x240 1 persp 8"
    "bigpersp 640x480 1 persp 8"
    "d9 320x240 1 ortho 9"
    "d10 320x240 1 ortho 10"
)
: >"$RES/rows.txt"
live=()
for r in "${ROWS[@]}"; do
    read -r key size zoom proj d <<<"$r"
    [[ " $DEPTHS " == *" $d "* ]] || continue      # depth not asked for (VIEWS_DEPTHS)
    echo "$r" >>"$RES/rows.txt"
    [[ " $baked " == *" $d "* ]] && live+=("$r")
done
[ ${#live[@]} -gt 0 ] || die "nothing to measure: no bake succeeded"
# view_args SIZE ZOOM PROJ: the options callgrind_frames, the viewer and osmesa_points share
view_args() { echo "--size $1 --zoom $2$([ "$3" = persp ] && echo " --perspective")"; }
lod_px() { [ "$1" = on ] && echo 1 || echo 0; }

# ---- instructions, drawn depth (cross-checked with the viewer), coverage ------------------------------
CG_OPTS=(--tool=callgrind --toggle-collect=mc_octree_render --compress-strings=no --compress-pos=no)
for r in "${live[@]}"; do
    read -r key size zoom proj d <<<"$r"
    name=$(printf 'b%02d' "$d")
    # shellcheck disable=SC2046
    set -- $(view_args "$size" "$zoom" "$proj")
    for lod in on off; do
        step "$key ($size, zoom $zoom, $proj, depth $d), level of detail $lod: callgrind, $CG_FRAMES-view turn"
        run valgrind "${CG_OPTS[@]}" --callgrind-out-file="$RES/cg.$key.$lod.out" "$BIN/$name-frames" "$CG_FRAMES" "$@" \
            --error "$(lod_px $lod)" >"$RES/cg.$key.$lod.txt" 2>"$RES/cg.$key.$lod.log"
        python3 tests/bench/bench_tools.py cg-total "$RES/cg.$key.$lod.out" >"$RES/cg.$key.$lod.total" ||
            die "cannot read $RES/cg.$key.$lod.out"
        # the viewer's own --bench reports the level it drew for the same view and bound
        run "$BIN/$name-view" --bench "$CG_FRAMES" "$@" --error "$(lod_px $lod)" >"$RES/viewer.$key.$lod.txt"
        vd=$(sed -n 's/^model .* depth \([0-9]*\) size .*/\1/p' "$RES/viewer.$key.$lod.txt")
        cd_=$(sed -n 's/^depth drawn: //p' "$RES/cg.$key.$lod.txt")
        [ -n "$vd" ] && [ "$vd" = "$cd_" ] || die "$key, level of detail $lod: the viewer drew depth '$vd', callgrind_frames '$cd_'"
    done
    step "$key: pixels covered and the frontal image, modelc (level of detail off) and Mesa"
    run "$BIN/$name-frames" 1 "$@" --error 0 --ppm "$RES/img.$key.modelc.ppm" --mask "$RES/img.$key.modelc.pgm" \
        >"$RES/img.$key.modelc.txt"
    run env LP_NUM_THREADS=0 "$BIN/$name-osmesa" --no-bench --views "$CG_FRAMES" "$@" --footprint \
        --ppm "$RES/img.$key.mesa.ppm" --mask "$RES/img.$key.mesa.pgm" >"$RES/img.$key.mesa.txt"
    python3 tests/bench/bench_tools.py image-cmp "$RES/img.$key.modelc.ppm" "$RES/img.$key.mesa.ppm" \
        "$RES/img.$key.modelc.pgm" "$RES/img.$key.mesa.pgm" >"$RES/img.$key.cmp" || die "image-cmp failed for $key"
done

# ---- image quality of the depth rows: the viewer's frame against the mesh reference -----------------------
for d in $baked; do
    name=$(printf 'b%02d' "$d")
    for lod in on off; do
        step "depth $d, level of detail $lod: PSNR against the mesh reference, $PSNR_VIEWS views at 320x240 zoom 1"
        run "$BIN/$name-psnr" "$RES/$name.ref" --size 320x240 --zoom 1 --views "$PSNR_VIEWS" --error "$(lod_px $lod)" \
            --ppm "$RES/psnr.$d.$lod" >"$RES/psnr.$d.$lod.txt"
    done
done

# ---- time: per round and row, modelc (on, off), Mesa, modelc again (A-B-A: the same machine load) ----------
: >"$RES/load.txt"
for round in $(seq 1 "$ROUNDS"); do
    for r in "${live[@]}"; do
        read -r key size zoom proj d <<<"$r"
        name=$(printf 'b%02d' "$d")
        # shellcheck disable=SC2046
        set -- $(view_args "$size" "$zoom" "$proj")
        step "timing round $round/$ROUNDS: $key (modelc on, off; Mesa; modelc on, off), $FRAMES-frame turn"
        cut -d' ' -f1 /proc/loadavg >>"$RES/load.txt"
        for ab in a mesa b; do
            if [ "$ab" = mesa ]; then
                run env LP_NUM_THREADS=0 "$BIN/$name-osmesa" --frames "$FRAMES" --views 0 "$@" --footprint \
                    >"$RES/time.$key.mesa.r$round.txt"
            else
                for lod in on off; do
                    run "$BIN/$name-frames" --time "$FRAMES" "$@" --error "$(lod_px $lod)" \
                        >"$RES/time.$key.$lod.r$round.$ab.txt"
                done
            fi
        done
    done
done
cut -d' ' -f1 /proc/loadavg >>"$RES/load.txt"

# ---- the section ----------------------------------------------------------------------------------------
pkgver() { dpkg-query -W -f='${Package} ${Version}' "$1" 2>/dev/null || echo "$1 ?"; }
{
    echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), nproc $(nproc)"
    echo "cc: $($CC --version | head -n1)"
    echo "valgrind: $(valgrind --version)"
    echo "mesa: $(pkgver libosmesa6)"
    echo "commit: $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
    echo "runtime changes: runtime/ with $(git status --porcelain -- runtime 2>/dev/null | wc -l) uncommitted file(s)"
    echo "render sha: $(sha256sum "$SNAP/src/octree_render.c" | cut -c1-16)"
    echo "model: $MODEL_FILE"
    echo "generator: $(cat "$RES/generator.txt")"
    echo "frames: $FRAMES"
    echo "rounds: $ROUNDS"
    echo "cg frames: $CG_FRAMES"
    echo "psnr views: $PSNR_VIEWS"
    echo "load end: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "seconds: $(($(date +%s) - T0))"
} >"$RES/meta.txt"
step "report"
python3 - "$RES" "$DEPTHS" >"$RES/section.md" <<'PY' || die "report failed"
import re, statistics, sys
sys.path.insert(0, "tests/bench")
from bench_tools import kv, num, read, fmt_int

res, depths = sys.argv[1], sys.argv[2].split()
meta = kv(f"{res}/meta.txt")
frames, rounds, cg_frames = int(meta["frames"]), int(meta["rounds"]), int(meta["cg frames"])
rows = [l.split() for l in read(f"{res}/rows.txt").splitlines() if l.strip()]
LABEL = {"bench": "320x240, zoom 1, orthographic (the benchmark)", "quarter": "320x240, zoom 0.25",
         "big": "640x480, zoom 1", "persp": "320x240, perspective (eye 2 cube sides)",
         "bigpersp": "640x480, perspective (eye 2 cube sides)", "d9": "320x240, zoom 1", "d10": "320x240, zoom 1"}
status = {d: read(f"{res}/bake.{d}.status", "not run") for d in depths}
med = statistics.median

def times(key, lod, clock):
    """per round: modelc = mean of its A and B runs"""
    out = []
    for r in range(1, rounds + 1):
        a = num(kv(f"{res}/time.{key}.{lod}.r{r}.a.txt").get(clock))
        b = num(kv(f"{res}/time.{key}.{lod}.r{r}.b.txt").get(clock))
        out.append((a + b) / 2)
    return out

def mesa_times(key, clock):
    return [num(kv(f"{res}/time.{key}.mesa.r{r}.txt").get(clock)) for r in range(1, rounds + 1)]

def point_size(s):
    """osmesa_points' "point size" line: a size, or per point ceil(LEAF * eye / distance)"""
    m = re.search(r"ceil\(([\d.]+) \* eye / distance\)", s)
    return f"per point: ceil({float(m.group(1)):.2f} px x eye / distance)" if m else f"{s.strip()} px"

R = {}
for key, size, zoom, proj, d in rows:
    if status[d] != "ok":
        continue
    mesa = kv(f"{res}/time.{key}.mesa.r1.txt")
    for lod in ("on", "off"):
        cg = kv(f"{res}/cg.{key}.{lod}.txt")
        ir = num(kv(f"{res}/cg.{key}.{lod}.total").get("Ir"))
        pts = num(cg.get("points drawn (sum)"))
        mc, mw = times(key, lod, "cpu ms per frame (median)"), times(key, lod, "ms per frame (median)")
        gc, gw = mesa_times(key, "cpu ms per frame (median)"), mesa_times(key, "ms per frame (median)")
        R[key, lod] = dict(
            depth=int(num(cg.get("depth drawn"))), leaves=pts / cg_frames, ir_frame=ir / cg_frames, ir_leaf=ir / pts,
            cpu=med(mc), wall=med(mw), mesa_cpu=med(gc), mesa_wall=med(gw),
            ratio=med(g / m for g, m in zip(gc, mc)), ratio_wall=med(g / m for g, m in zip(gw, mw)),
            ratios=[g / m for g, m in zip(gc, mc)],
            mesa_points=int(num(mesa.get("points"))), point_size=point_size(mesa.get("point size", "")),
            viewer=kv(f"{res}/viewer.{key}.{lod}.txt"),
            viewer_depth=re.search(r"^model \S+ depth (\d+) ", read(f"{res}/viewer.{key}.{lod}.txt"), re.M).group(1))

L = []
A = L.append
loads = [float(x) for x in read(f"{res}/load.txt").split()]
renderer = kv(f"{res}/time.bench.mesa.r1.txt") if ("bench", "on") in R else {}
A("## The point renderer at every view: level of detail on and off, beside Mesa")
A("")
A(f"Written by `tests/bench/views.sh` (`make bench-views`) on {meta['date']} in {meta['seconds']} s; do not edit by hand: "
  "run it again. bunny00 baked at depths " + ", ".join(depths) + " (`build/bench/views/bNN`, one bake each); each row drawn by "
  "mc_octree_render with the screen-space level of detail **on** (`max_error` = one pixel, `MC_LOD_PIXEL`, the viewer's "
  "default `--error 1`: the shallowest level whose nodes span at most a pixel) and **off** (`max_error` 0: the bake's depth), "
  "every other `mc_octree_options` field at its default (zero), e.g. the default footprint (a leaf larger than a pixel "
  "is drawn as a ceil(side) square). Leaves drawn, instructions and images are those of the runtime as the run found it "
  "(see the source line below).")
A("")
A(f"- **Instructions**: `valgrind --tool=callgrind --toggle-collect=mc_octree_render` on `tests/bench/callgrind_frames.c`, "
  f"a {cg_frames}-view turn of yaw (frame i at i * 4096 / {cg_frames} angle units), so only the render call and its "
  "callees are counted (not mc_clear). Ir per frame = total / frames; Ir per drawn leaf = total / sum of mc_stats.points "
  "(leaves that landed on the target). Depth drawn = mc_stats.depth, the same as the viewer's `--bench` prints for the "
  "same view and bound (checked for every row).")
A(f"- **Time**: median over a {frames}-frame turn of the process CPU time per frame: `callgrind_frames --time` "
  "(mc_clear + mc_octree_render, no finishing) and Mesa's llvmpipe on one thread (`LP_NUM_THREADS=0`, "
  "`tests/bench/osmesa_points.c`: glClear + glDrawArrays of a VBO + glFinish) drawing **every leaf of the bake** with the "
  "same projection, `--footprint`: GL_POINTS as large as modelc's footprint of a leaf of the bake's depth (ceil of its "
  "side on screen; per point in perspective, from a vertex shader). "
  f"{rounds} rounds, each row A-B-A within a round (modelc on and off, Mesa, modelc on and off); a round's modelc time is "
  "the mean of its two runs; ms = median over rounds; **Mesa / modelc** = median over rounds of the ratio in the same round. "
  "CPU time is the headline as in section 3 (a long Mesa frame is preempted more often on a shared machine); wall "
  "clock below.")
if renderer:
    A(f"- Mesa: {renderer.get('renderer', '?')}, {renderer.get('version', '?')}, {meta['mesa']}; {meta['cc']}, -O2; "
      f"{meta['valgrind']}; {meta['cpu']}. Runtime and generator: the working tree at commit {meta['commit']} ({meta['runtime changes']}), "
      f"copied to build/bench/views/src/runtime (octree_render.c sha256 {meta['render sha']}); the bakes by a copy of "
      f"{meta['generator']} made at the start, build/bench/views/bin/modelc.")
if loads:
    A(f"- 1-minute load average during the timings: {min(loads):.2f} to {max(loads):.2f} on a {meta['cpu'].split('nproc ')[-1]}-CPU machine"
      + (" (shared with other work: absolute times are inflated and noisy; the instruction counts are not)." if max(loads) > 1.6 else "."))
A("")
def measured():
    """(view, bake depth, level of detail, results) of every row whose bake was made"""
    for key, size, zoom, proj, d in rows:
        if status[d] == "ok":
            for lod in ("on", "off"):
                yield key, d, lod, R[key, lod]


A("| view | bake | level of detail | depth drawn | leaves drawn per frame | Ir per frame | Ir per drawn leaf | modelc ms | "
  "Mesa points | Mesa point size | Mesa ms | **Mesa / modelc** |")
A("|---|---:|---|---:|---:|---:|---:|---:|---:|---|---:|---:|")
for key, size, zoom, proj, d in rows:
    for lod in ("on", "off"):
        name = LABEL[key]
        if status[d] != "ok":
            A(f"| {name} | depth {d} | {lod} | {status[d]} | | | | | | | | |")
            continue
        r = R[key, lod]
        A(f"| {name} | depth {d} | {lod} | {r['depth']} | {fmt_int(r['leaves'])} | {fmt_int(r['ir_frame'])} | "
          f"{r['ir_leaf']:.2f} | {r['cpu']:.3f} | {fmt_int(r['mesa_points'])} | {r['point_size']} | "
          f"{r['mesa_cpu']:.2f} | **{r['ratio']:.1f}x** |")
A("")
A("Wall clock (same runs), the per-round CPU-time ratios, and the viewer's `--bench "
  f"{cg_frames}` for the same view (its level; its ms include the default finishing, one run, not interleaved):")
A("")
A("| view | bake | level of detail | modelc wall ms | Mesa wall ms | wall ratio | CPU ratio per round | viewer depth | viewer ms |")
A("|---|---:|---|---:|---:|---:|---|---:|---:|")
for key, d, lod, r in measured():
    A(f"| {LABEL[key]} | depth {d} | {lod} | {r['wall']:.3f} | {r['mesa_wall']:.2f} | {r['ratio_wall']:.1f}x | "
      + ", ".join(f"{x:.1f}" for x in r["ratios"])
      + f" | {r['viewer_depth']} | {num(r['viewer'].get('ms per frame (median)')):.3f} |")
A("")
A(f"Same pixels? Mean pixels covered over the {cg_frames}-view turn by modelc with the level of detail off (the bake's "
  "depth, the other options at their defaults; its leaves drawn per frame are in the first table) and by Mesa (every leaf "
  "of the bake), and the frontal frames compared pixel by pixel (`bench_tools.py image-cmp`; PPM/PGM in "
  "build/bench/views/res/img.*):")
A("")
A("| view | bake | pixels modelc | pixels Mesa | frontal image, modelc vs Mesa |")
A("|---|---:|---:|---:|---|")
for key, size, zoom, proj, d in rows:
    if status[d] != "ok":
        continue
    pm = num(kv(f"{res}/cg.{key}.off.txt").get(f"pixels covered per view (mean of {cg_frames} views)"))
    pg = num(kv(f"{res}/img.{key}.mesa.txt").get(f"pixels covered per view (mean of {cg_frames} views)"))
    A(f"| {LABEL[key]} | depth {d} | {fmt_int(pm)} | {fmt_int(pg)} | {read(f'{res}/img.{key}.cmp')} |")
A("")

# image quality of the depth rows
P = {}
for d in depths:
    for lod in ("on", "off"):
        p = kv(f"{res}/psnr.{d}.{lod}.txt")
        if p:
            P[d, lod] = dict(depth=int(num(p.get("depth drawn"))), psnr=num(p.get("psnr pooled")),
                             worst=num(p.get("psnr worst view")), cov=num(p.get("coverage differs")))
pv = meta["psnr views"]
A(f"Image quality at 320x240, zoom 1 (`tests/bench/views_psnr.c`): the viewer's frame (mc_host_scene_draw: the default "
  "footprint, the bound, then mc_finish with the default fill) against the double-precision mesh reference "
  "(runtime/ref/mesh_ref.c: the original triangles from the bake's `--dump-reference`, coloured through the bake's own "
  f"palette), both on black, as tests/accuracy/acc.c scores them; {pv} views of a turn of yaw (frame i at i * 4096 / {pv}); "
  "PSNR over R, G, B with the squared errors of all views pooled, the worst single view, and the coverage difference "
  "(pixels covered by only one image / by either). Ir per frame from the table above.")
A("")
A("| bake | level of detail | depth drawn | PSNR dB | worst view dB | coverage differs | Ir per frame |")
A("|---:|---|---:|---:|---:|---:|---:|")
key_of = {"8": "bench", "9": "d9", "10": "d10"}
for d in depths:
    for lod in ("on", "off"):
        if (d, lod) not in P:
            A(f"| depth {d} | {lod} | {status[d]} | | | | |")
            continue
        p = P[d, lod]
        k = key_of.get(d)
        irf = fmt_int(R[k, lod]["ir_frame"]) if (k, lod) in R else "-"
        A(f"| depth {d} | {lod} | {p['depth']} | {p['psnr']:.2f} | {p['worst']:.2f} | {100 * p['cov']:.2f} % | {irf} |")
A("")

# the renderer's targets for these views, each computed from the rows above
ok = lambda c: "**meets**" if c else "**misses**"
A("The figures against their targets (level of detail on, the viewer's default):")
A("")
b = R.get(("bench", "on"))
if b and ("quarter", "on") in R:
    q = R["quarter", "on"]
    A(f"- zoom 0.25 at 320x240: {fmt_int(q['ir_frame'])} Ir per frame (depth {q['depth']} drawn) = 1/{b['ir_frame'] / q['ir_frame']:.1f} "
      f"of zoom 1's {fmt_int(b['ir_frame'])}: {ok(q['ir_frame'] <= b['ir_frame'] / 8)} the <= 1/8 figure "
      f"(level of detail off: {fmt_int(R['quarter', 'off']['ir_frame'])}, 1/{b['ir_frame'] / R['quarter', 'off']['ir_frame']:.1f}).")
for d, k in (("9", "d9"), ("10", "d10")):
    if d not in depths:
        continue
    if not b or (k, "on") not in R or (d, "on") not in P or ("8", "on") not in P:
        A(f"- depth {d} at 320x240 zoom 1: not measured ({status.get(d, 'not run')}).")
        continue
    x, p, p8 = R[k, "on"], P[d, "on"], P["8", "on"]
    A(f"- depth {d} bake at 320x240 zoom 1: {fmt_int(x['ir_frame'])} Ir per frame (depth {x['depth']} drawn) = "
      f"{x['ir_frame'] / b['ir_frame']:.2f}x the depth-8 bake's: {ok(x['ir_frame'] <= 1.3 * b['ir_frame'])} the <= 1.3x "
      f"figure; PSNR {p['psnr']:.2f} dB against depth 8's {p8['psnr']:.2f} dB (compared as printed): "
      f"{ok(round(p['psnr'], 2) >= round(p8['psnr'], 2))} the same-quality condition (not lower than depth 8's). "
      f"Level of detail off: {R[k, 'off']['ir_frame'] / b['ir_frame']:.2f}x the instructions, {P[d, 'off']['psnr']:.2f} dB.")
if ("big", "on") in R:
    x = R["big", "on"]
    A(f"- 640x480 zoom 1: {x['ir_leaf']:.2f} Ir per drawn leaf (depth {x['depth']} drawn, {fmt_int(x['leaves'])} leaves): "
      f"{ok(x['ir_leaf'] <= 40)} the <= 40 figure.")
if ("persp", "on") in R:
    x = R["persp", "on"]
    A(f"- perspective at 320x240: {x['ir_leaf']:.2f} Ir per drawn leaf (depth {x['depth']} drawn, {fmt_int(x['leaves'])} leaves): "
      f"{ok(x['ir_leaf'] <= 50)} the <= 50 figure.")
for d in depths:
    if status[d] != "ok" and d not in ("9", "10"):   # 9 and 10 are reported above
        A(f"- depth {d}: {status[d]}.")
bakes = []
for d in depths:
    t = read(f"{res}/bake.{d}.time").split()
    s = read(f"{res}/bake.{d}.seconds")
    if status[d] != "ok":
        bakes.append(f"depth {d} not baked after {s} s")
        continue
    bakes.append(f"depth {d} {s} s" + (f", {int(t[-1]) / 1024:.0f} MB peak" if len(t) >= 2 and t[-1].isdigit() else ""))
A("")
A("Bakes (wall time, peak resident memory of modelc): " + "; ".join(bakes) + ".")
print("\n".join(L))
PY
# the commands, once each in order of first use (repeats counted), as tests/bench/run.sh lists them
mapfile -t cmds < <(awk '{ if (!($0 in n)) o[++k] = $0; n[$0]++ } END { for (i = 1; i <= k; i++) print o[i] (n[o[i]] > 1 ? "    # x" n[o[i]] : "") }' \
    "$RES/commands.log")
write_section "$results" views "$RES/section.md" "${cmds[@]}" >/dev/null
step "wrote the views section of $results"
sed -n '/^| view | bake | level of detail | depth drawn/,/^$/p' "$RES/section.md"
