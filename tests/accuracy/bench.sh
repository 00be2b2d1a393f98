#!/usr/bin/env bash
# make bench-accuracy: run time against error.
#
# For each model (ACC_MODELS, default "bunny00 nefertiti") it bakes the octree at depths 5..10, dumps
# the original mesh once (modelc --dump-reference) and builds tests/accuracy/acc.c for each setting:
#   - fixed point, MC_FRAC_BITS 15 (the default), depth 5..10
#   - "float": the runtime built with tests/accuracy/pos_single.h for its positions (config.h
#     MC_POS_HEADER: single-precision screen positions, the same walk),
#     depth 5..10
#   - "exact": the double-precision octree walk of runtime/ref (mc_ref_points, exact leaf positions)
#     with the runtime's footprints and finishing, depth 5..10: the error floor (acc.c)
#   - fixed point, MC_FRAC_BITS 8 10 12 14 16 18 at depth 8, and 8 12 18 at depth 10
#   - fixed point, MC_FRAC_BITS 19..24 at depth 8: compiled and run, but at 320x240 mc_octree_render refuses
#     the target (MC_TARGET_MAX = 2^(27 - F) pixels), recorded as status "size"
#   - the level-selection bound: fixed point F = 15 at depths ACC_LOD_DEPTHS (default 8 and 10) with
#     mc_octree_options.max_error at ACC_ERRORS pixels (default 1 2 4 8; acc.c --error): the renderer draws
#     the shallowest level whose nodes span at most the bound, never deeper than the bake (every other
#     setting: bound off, the bake's depth)
# Each setting renders 12 views (yaw 0/20/40/60 degrees with pitch 0/5/10/15, zoom 1, 1.5, 2) with
# each splat and fill the runtime has, against the mesh reference (runtime/ref/mesh_ref.c), and times
# them (median of ACC_FRAMES frames, default 7, at least 20 ms). Instructions per frame: callgrind on
# every setting that renders, on 4 of the 12 views (acc.c --cg). About 10 minutes on 2 shared cores.
#
# Writes build/bench/accuracy/{views.csv, cg.csv}, then tests/bench/accuracy.csv (one row per
# setting, means over the views), tests/bench/accuracy.png (error against time, Pareto front) and the
# "bench-accuracy" section of tests/bench/RESULTS.md.
set -euo pipefail
cd "$(dirname "$0")/../.."

MODELC=${MODELC:-build/bin/modelc}
MODELS=${ACC_MODELS:-bunny00 nefertiti}
FRAMES=${ACC_FRAMES:-7}
SIZE=${ACC_SIZE:-320x240}
CC=${CC:-gcc}
[ "$CC" = cc ] && CC=gcc
OPT="-O2 -g"
OUT=build/bench/accuracy
T0=$(date +%s)
step() { printf '[bench-accuracy %4ss] %s\n' "$(($(date +%s) - T0))" "$*"; }
die() { echo "bench-accuracy: $*" >&2; exit 1; }

for tool in valgrind callgrind_annotate gnuplot python3 "$CC"; do
    command -v "$tool" >/dev/null || die "$tool not found: run make deps"
done
[ -x "$MODELC" ] || die "$MODELC missing: run make gen"
mkdir -p "$OUT/bakes" "$OUT/obj" "$OUT/bin" "$OUT/cg" "$OUT/log"

DEPTHS="5 6 7 8 9 10"
LOD_DEPTHS=${ACC_LOD_DEPTHS:-8 10}
ERRORS=${ACC_ERRORS:-1 2 4 8}
FRACS_D8="8 10 12 14 16 18 19 20 21 22 23 24"
FRACS_D10="8 12 18"

# ---- runtime objects per fraction width or float (and the references, which include config.h) ----
# rebuilt whenever any runtime source or header changes (others edit the runtime while this runs)
STAMP=$(cat runtime/src/*.c runtime/src/*.h runtime/include/modelc/*.h runtime/ref/*.c runtime/ref/*.h | sha256sum | cut -c1-16)
cfg_flags() {   # F, or "float" -> the runtime's configuration flags
    if [ "$1" = float ]; then echo "-DMC_FLOAT=1 -DMC_POS_HEADER=\"pos_single.h\" -Itests/accuracy"; else echo "-DMC_FRAC_BITS=$1"; fi
}
rt_objs() {   # F or "float" -> object directory
    local d=$OUT/obj/rt$1 cfg
    cfg=$(cfg_flags "$1")
    if [ "$(cat "$d/.done" 2>/dev/null)" != "$STAMP" ]; then
        rm -rf "$d"
        mkdir -p "$d"
        for s in runtime/src/*.c; do
            # shellcheck disable=SC2086
            $CC $OPT -std=c99 -ffreestanding -Wall -Wextra -Werror -Iruntime/include $cfg \
                -c -o "$d/$(basename "${s%.c}").o" "$s" || return 1
        done
        for s in runtime/ref/ref.c runtime/ref/mesh_ref.c; do
            # shellcheck disable=SC2086
            $CC $OPT -std=c99 -Wall -Wextra -Werror -Iruntime/include $cfg \
                -c -o "$d/$(basename "${s%.c}").o" "$s" || return 1
        done
        echo "$STAMP" >"$d/.done"
    fi
    echo "$d"
}

# ---- bakes ----------------------------------------------------------------------------------------
model_file() {
    make -s --no-print-directory -f - print <<EOF
include models/catalogue.mk
print: ; @echo build/models/\$(notdir \$($1.src))
EOF
}
{ echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"; echo "commit: $(git rev-parse --short HEAD 2>/dev/null)";
  echo "runtime sources: $STAMP, $(git status --porcelain -- runtime | wc -l) files with uncommitted changes";
  echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"; } >"$OUT/meta.txt"
step "runtime objects (F = 15)"
rt_objs 15 >/dev/null
for m in $MODELS; do
    src=$(model_file "$m")
    [ -f "$src" ] || make -s "$src" || die "$src missing: run make models"
    opts=$(make -s --no-print-directory -f - print <<EOF
include models/catalogue.mk
print: ; @echo \$($m.opts)
EOF
)
    opts=$(echo " $opts " | sed 's/ --depth [0-9]* / /')
    for d in $DEPTHS; do
        name=${m}_d$d
        if [ ! -f "$OUT/bakes/$name/budget.json" ] || [ "$MODELC" -nt "$OUT/bakes/$name/budget.json" ]; then
            step "$m: bake depth $d"
            rm -rf "${OUT:?}/bakes/$name"
            dump=()
            [ "$d" = 5 ] && dump=(--dump-reference "$OUT/bakes/$m.ref")
            "$MODELC" "$src" -o "$OUT/bakes" --name "$name" --depth "$d" -q $opts "${dump[@]}" \
                >"$OUT/log/$name.bake.log" 2>&1 || { cat "$OUT/log/$name.bake.log"; die "bake $name failed"; }
            rm -rf "${OUT:?}/obj/$name"
        fi
        if [ "$(cat "$OUT/obj/$name/.done" 2>/dev/null)" != "$STAMP" ]; then
            rm -rf "${OUT:?}/obj/$name"
            mkdir -p "$OUT/obj/$name"
            for s in "$OUT/bakes/$name/${name}_data_"*.c "$OUT/bakes/$name/${name}_octree.c"; do
                $CC $OPT -std=c99 -ffreestanding -Wall -Wextra -Iruntime/include -c \
                    -o "$OUT/obj/$name/$(basename "${s%.c}").o" "$s"
            done
            echo "$STAMP" >"$OUT/obj/$name/.done"
        fi
    done
done

# ---- the settings: model depth build frac lod (the level-selection bound in pixels, 0 = off) -----
settings=()
for m in $MODELS; do
    for d in $DEPTHS; do settings+=("$m $d fixed 15 0" "$m $d float 15 0" "$m $d exact 15 0"); done
    for f in $FRACS_D8; do settings+=("$m 8 fixed $f 0"); done
    for f in $FRACS_D10; do settings+=("$m 10 fixed $f 0"); done
    # after the bound-off settings, which build the programs these run again with --error
    for d in $LOD_DEPTHS; do for e in $ERRORS; do settings+=("$m $d fixed 15 $e"); done; done
done

echo "model,depth,build,frac,lod,yaw,pitch,zoom,splat,fill,psnr,ssim,coverage,ms,cpu_ms,status" >"$OUT/views.csv"
echo "model,depth,build,frac,lod,part,ir" >"$OUT/cg.csv"
cg_jobs=()
for s in "${settings[@]}"; do
    read -r m d build f lod <<<"$s"
    [ "$build" = fixed ] || [ "$f" = 15 ] || continue
    name=${m}_d$d
    exe=$OUT/bin/acc-$name-$build-f$f
    tag="$m,$d,$build,$f,$lod"
    key=$f exact=0
    [ "$build" = float ] && key=float
    [ "$build" = exact ] && exact=1
    if [ "$lod" = 0 ]; then
        step "$tag: build"
        if ! rt=$(rt_objs "$key" 2>"$OUT/log/rt$key.log"); then
            echo "$m,$d,$build,$f,$lod,,,,,,,,,,,compile" >>"$OUT/views.csv"
            continue
        fi
        # shellcheck disable=SC2046
        $CC $OPT -std=c99 -Wall -Wextra -Werror -Iruntime/include -Iruntime/ref -Iruntime/front/host $(cfg_flags "$key") \
            -DACC_SCENE="mc_octree_$name" -DACC_EXACT=$exact -o "$exe" tests/accuracy/acc.c "$rt"/*.o \
            "$OUT/obj/$name"/*.o -lm
    elif ! grep -q "^$m,$d,$build,$f,0,.*,ok\$" "$OUT/views.csv"; then
        echo "$m,$d,$build,$f,$lod,,,,,,,,,,,compile" >>"$OUT/views.csv"
        continue
    fi
    bound=""
    [ "$lod" = 0 ] || bound=" (level-selection bound $lod px)"
    step "$tag: render and time 12 views$bound"
    "$exe" "$OUT/bakes/$m.ref" --tag "$tag" --frames "$FRAMES" --size "$SIZE" --error "$lod" >>"$OUT/views.csv"
    # instruction counts: every setting that renders at this size (F <= 18 at 320x240)
    if grep -q "^$tag,.*,ok\$" "$OUT/views.csv"; then cg_jobs+=("$tag $exe $lod"); fi
done

step "callgrind: ${#cg_jobs[@]} settings, 4 views each, two at a time"
printf '%s\n' "${cg_jobs[@]}" | xargs -P 2 -L 1 bash -c '
    tag=$0 exe=$1 lod=$2 out='"$OUT"'/cg/$(basename "$1")-e$2.out
    valgrind --tool=callgrind --toggle-collect="acc_*" --callgrind-out-file="$out" "$exe" --cg --size '"$SIZE"' --error "$lod" \
        >/dev/null 2>"$out.log" || { echo "callgrind failed: $exe --error $lod" >&2; exit 0; }
    callgrind_annotate --inclusive=yes --threshold=100 "$out" 2>/dev/null |
        sed -n "s/^ *\([0-9,]*\) ([^)]*) *[^ ]*:\(acc_[a-z_]*\) .*/\2 \1/p" | tr -d , |
        while read -r part ir; do echo "$tag,$part,$ir"; done >"$out.csv"'
for s in "${cg_jobs[@]}"; do
    read -r _ exe lod <<<"$s"
    cat "$OUT/cg/$(basename "$exe")-e$lod.out.csv" >>"$OUT/cg.csv" 2>/dev/null || true
done

step "report"
python3 tests/accuracy/report.py "$OUT/views.csv" "$OUT/cg.csv" tests/bench/accuracy.csv "$OUT/plot" \
    tests/bench/RESULTS.md --frames "$FRAMES" --size "$SIZE" --seconds "$(($(date +%s) - T0))"
gnuplot "$OUT/plot/accuracy.gp"
cp "$OUT/plot/accuracy.png" tests/bench/accuracy.png
step "wrote tests/bench/accuracy.csv, tests/bench/accuracy.png and the bench-accuracy section of tests/bench/RESULTS.md"
