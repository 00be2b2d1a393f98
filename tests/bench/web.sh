#!/usr/bin/env bash
# make bench-web: the web viewer's module in headless Chromium against the native viewer, side by side
# in one run. Bakes bunny00 once (build/bench/web/b08), links its native viewer as the Makefile does and
# builds its page (runtime/front/web/build.sh) from the same bake and runtime; then, per size and round,
# native --bench, the page (tests/bench/web_bench.js through tests/web/cdp.py), native again; ratio = the page's median over the
# mean of the two native medians around it; the figure is the median over rounds. Then the same for
# the mesh renderer: bunny00 baked --as both (build/bench/web/m05, all 75,408 faces), its full level
# shaded and in lines at 320x240 (native --mode STYLE --bench, the page's mcw_draw_mesh). Writes the
# "web" section of tests/bench/RESULTS.md (or of the file given as $1).
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/lib.sh            # model_file
. tests/bench/section.sh  # write_section
. tests/bench/common.sh   # CC, OPT, RT_FLAGS, HOST_FLAGS, bench_quote

results=${1:-tests/bench/RESULTS.md}
MODELC=${MODELC:-build/bin/modelc}
ROUNDS=${WEB_ROUNDS:-3}
FRAMES=${WEB_FRAMES:-200}
SIZES=${WEB_SIZES:-320x240 640x480}
MESH_SIZE=${WEB_MESH_SIZE:-320x240}
MESH_STYLES="shaded lines"
OUT=build/bench/web
RES=$OUT/res
T0=$(date +%s)
die() { echo "bench-web: $*" >&2; exit 1; }
step() { printf '[bench-web %4ss] %s\n' "$(($(date +%s) - T0))" "$*"; }
run() {
    local q
    q=$(bench_quote "$@")
    printf '%s\n' "$q" >>"$RES/commands.log"
    "$@" || die "failed (status $?): $q"
}

for tool in chromium clang python3 "$CC"; do command -v "$tool" >/dev/null || die "$tool not found (make deps)"; done
[ -x "$MODELC" ] || die "$MODELC missing (make gen)"
model=$(model_file bunny00) || die "bunny00 missing (make models)"
rm -rf "$OUT" && mkdir -p "$RES"
: >"$RES/commands.log"

step "bake and builds"
run "$MODELC" "$model" -o "$OUT" --name b08 --depth 8 -q
inc="-Iruntime/include -Iruntime/front/host"
# shellcheck disable=SC2086
run $CC $OPT $RT_FLAGS $inc -ffunction-sections -fdata-sections -o "$OUT/b08-view" "$OUT"/b08/*.c runtime/src/*.c \
    runtime/front/host/*.c runtime/front/common/*.c -Wl,--gc-sections -lm
run runtime/front/web/build.sh "$OUT" b08
run "$MODELC" "$model" -o "$OUT" --name m05 --depth 5 --as both -q
# shellcheck disable=SC2086
run $CC $OPT $RT_FLAGS $inc -ffunction-sections -fdata-sections -o "$OUT/m05-view" "$OUT"/m05/*.c runtime/src/*.c \
    runtime/front/host/*.c runtime/front/common/*.c -Wl,--gc-sections -lm
run runtime/front/web/build.sh "$OUT" m05
mesh_faces=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["pmesh"]["faces"])' "$OUT/m05/budget.json")
mesh_wasm_bytes=$(stat -c %s "$OUT/m05/web/m05.wasm")
clang_version=$(clang --version | head -n 1)
chromium_version=$(chromium --version 2>/dev/null | head -n 1)
wasm_bytes=$(stat -c %s "$OUT/b08/web/b08.wasm")

chrome_bench() {   # SIZE [BAKE STYLE]: "ms points" of the page's module at that size (real time, not virtual)
    local w=${1%x*} h=${1#*x} bake=${2:-b08} style=${3:-0} js
    js="$(cat tests/bench/web_bench.js)($w, $h, $FRAMES, $style)"
    printf '%s\n' "python3 tests/web/cdp.py file://$PWD/$OUT/$bake/web/index.html --eval \"\$(cat tests/bench/web_bench.js)($w, $h, $FRAMES, $style)\"" >>"$RES/commands.log"
    python3 tests/web/cdp.py "file://$PWD/$OUT/$bake/web/index.html" --eval "$js" |
        python3 -c 'import json, sys; r = json.load(sys.stdin); print("%.4f %d" % (r["ms"], r["points"]))'
}
native_bench() {   # SIZE [BAKE MODE]: the native viewer's median ms
    run "$OUT/${2:-b08}-view" --bench "$FRAMES" --size "$1" ${3:+--mode $3} >"$RES/native.txt"
    sed -n 's/^ms per frame (median): //p' "$RES/native.txt"
}

step "timing: $ROUNDS rounds of native, Chromium, native at $SIZES ($FRAMES frames each)"
: >"$RES/rounds.txt"
load0=$(cut -d' ' -f1 /proc/loadavg)
for r in $(seq "$ROUNDS"); do
    for size in $SIZES; do
        a=$(native_bench "$size")
        web=$(chrome_bench "$size") || die "the page at $size printed no timing"
        b=$(native_bench "$size")
        echo "$size $r $a $b $web" >>"$RES/rounds.txt"
        step "round $r $size: native $a, $b ms; page: $web"
    done
done
step "mesh timing: $ROUNDS rounds of native, Chromium, native, $MESH_STYLES at $MESH_SIZE"
: >"$RES/mesh_rounds.txt"
for r in $(seq "$ROUNDS"); do
    for style in $MESH_STYLES; do
        code=$([ "$style" = shaded ] && echo 1 || echo 2)
        a=$(native_bench "$MESH_SIZE" m05 "$style")
        web=$(chrome_bench "$MESH_SIZE" m05 "$code") || die "the mesh page ($style) printed no timing"
        b=$(native_bench "$MESH_SIZE" m05 "$style")
        echo "$style $r $a $b $web" >>"$RES/mesh_rounds.txt"
        step "round $r $style: native $a, $b ms; page: $web"
    done
done
load1=$(cut -d' ' -f1 /proc/loadavg)

python3 - "$RES/rounds.txt" "$SIZES" "$RES/mesh_rounds.txt" >"$RES/section.md" <<PY
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
mesh_rows = [l.split() for l in open(sys.argv[3])]
sizes = sys.argv[2].split()
out = []
out.append('## Web viewer: the module in Chromium against the native viewer')
out.append('')
out.append('Written by \`tests/bench/web.sh\` (\`make bench-web\`) on $(date -u '+%Y-%m-%d %H:%M:%S UTC') in $(( $(date +%s) - T0 )) s; do not edit by hand: run it again. '
           'bunny00 baked once at depth 8 (\`build/bench/web/b08\`); the native viewer (gcc -O2, the Makefile\'s flags) and the page\'s module '
           '(\`runtime/front/web/build.sh\`: clang --target=wasm32 -nostdlib -O2, wasm-ld, $wasm_bytes bytes, no imports) built from that bake and the working tree at commit $(git rev-parse --short HEAD) '
           '($(git status --porcelain runtime | wc -l) uncommitted runtime file(s)). $clang_version; $chromium_version, headless, one tab.')
out.append('')
out.append('- **Native**: \`b08-view --bench $FRAMES --size WxH\`: the median over a turn of yaw of the time of mc_clear + mc_octree_render + mc_finish (the default fill), level-of-detail bound 1 px.')
out.append('- **Chromium**: \`tests/bench/web_bench.js\` evaluated in the page (\`tests/web/cdp.py\`, real time): a warm-up of a turn and 3 s, then the same $FRAMES views through the module\'s mcw_draw, which does the same and also widens the frame to RGBA for the canvas; the median over batches of 10 frames of performance.now() time over the batch (Chromium coarsens the clock to 0.1 ms).')
out.append('- Each round runs native, Chromium, native at one size; a round\'s ratio is Chromium over the mean of the two native runs; the figure is the median over $ROUNDS rounds. Wall-clock time on a shared 2-CPU machine; 1-minute load average $load0 before and $load1 after.')
out.append('')
out.append('| size | points drawn per frame | native ms (median of rounds) | Chromium ms (median of rounds) | **Chromium / native** | ratio per round |')
out.append('|---|---:|---:|---:|---:|---|')
summary = []
for s in sizes:
    rs = [r for r in rows if r[0] == s]
    nat = [(float(r[2]) + float(r[3])) / 2 for r in rs]
    web = [float(r[4]) for r in rs]
    ratio = [wb / n for wb, n in zip(web, nat)]
    pts = rs[0][5]
    med = statistics.median(ratio)
    out.append('| %s | %s | %.3f | %.3f | **%.2fx** | %s |' % (s, '{:,}'.format(int(pts)), statistics.median(nat), statistics.median(web), med,
                                                           ', '.join('%.2f' % x for x in ratio)))
    summary.append('%s: %.2fx' % (s, med))
out.append('')
out.append('Against the figure (time per frame in Chromium within 3x the native viewer\'s): ' + '; '.join(
    '%s **%s**' % (x, 'meets' if float(x.split(': ')[1][:-1]) <= 3 else 'misses') for x in summary) + '.')
out.append('')
out.append('The mesh renderer the same way: bunny00 baked \`--as both\` (\`build/bench/web/m05\`, $mesh_faces faces; the module $mesh_wasm_bytes bytes), its full level at $MESH_SIZE. '
           'Native: \`m05-view --mode STYLE --bench $FRAMES --size $MESH_SIZE\` (mc_front_mesh_frame, the vertex cache, the sparse depth buffer for the hidden lines). '
           'Chromium: the same turn through the module\'s mcw_draw_mesh (the same sequence, then RGBA for the canvas), timed as above. Drawn per frame: faces that covered a pixel (shaded), line pixels (lines).')
out.append('')
out.append('| style | drawn per frame | native ms (median of rounds) | Chromium ms (median of rounds) | **Chromium / native** | ratio per round |')
out.append('|---|---:|---:|---:|---:|---|')
for st in "$MESH_STYLES".split():
    rs = [r for r in mesh_rows if r[0] == st]
    nat = [(float(r[2]) + float(r[3])) / 2 for r in rs]
    web = [float(r[4]) for r in rs]
    ratio = [wb / n for wb, n in zip(web, nat)]
    out.append('| %s | %s | %.3f | %.3f | **%.2fx** | %s |' % (st, '{:,}'.format(int(rs[0][5])), statistics.median(nat), statistics.median(web),
                                                           statistics.median(ratio), ', '.join('%.2f' % x for x in ratio)))
print('\n'.join(out))
PY
mapfile -t cmds <"$RES/commands.log"
write_section "$results" web "$RES/section.md" "${cmds[@]}" >/dev/null
step "wrote the web section of $results"
sed -n '/^| size |/,/^$/p; /^| style |/,/^$/p' "$RES/section.md"
