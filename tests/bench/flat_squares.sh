#!/usr/bin/env bash
# The point renderer's two walks over orthographic 2x2 squares (config.h MC_FLAT_SQUARES: 0, a loop
# per level d-1 node; 1, a 64-bit mask per level d-2 node, the default on x86-64) side by side in one
# run: bunny00 at depth 8 and 640x480 (leaves two pixels across), callgrind_frames built once each way
# from the same runtime copy; callgrind instructions per drawn point of mc_octree_render over the
# 20-view turn, CPU ms per frame (rounds of the 200-frame turn, the two builds alternately, the
# order swapped every round; medians over rounds) and whether both draw the same pixels. Appends
# (replacing an earlier copy) a marked section to RESULTS.md; make bench runs it after the depth test.
#   tests/bench/flat_squares.sh [RESULTS.md]
#   FLAT_SIZE (640x480), FLAT_ROUNDS (7), FLAT_FRAMES (200), FLAT_RUNTIME_REV (empty: the working
#   tree's runtime/; else a git revision to take it from)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh   # write_section
. tests/lib.sh   # runtime_snapshot, model_file
results=${1:-tests/bench/RESULTS.md}
size=${FLAT_SIZE:-640x480} rounds=${FLAT_ROUNDS:-7} frames=${FLAT_FRAMES:-200} rev=${FLAT_RUNTIME_REV:-}
out=build/bench/flat
modelc=build/bin/modelc
[ -x "$modelc" ] || { echo "flat_squares.sh: $modelc missing: run make gen" >&2; exit 1; }
src=$(model_file bunny00) || { echo "flat_squares.sh: bunny00 cannot be extracted: run make models" >&2; exit 1; }
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
runtime_from=$(runtime_snapshot "$out/src" "$rev") || { echo "flat_squares.sh: cannot copy the runtime" >&2; exit 1; }
rt=$out/src/runtime
rm -rf "$out/bunny00_d8"
run "$modelc" "$src" -o "$out" --name bunny00_d8 --depth 8 -q
others=()
for f in "$rt"/src/*.c; do [ "$(basename "$f")" = octree_render.c ] || others+=("$f"); done
for s in 0 1; do
    run gcc -O2 -g -std=c99 -ffreestanding -Wall -Wextra -DMC_FLAT_SQUARES=$s -I"$rt/include" -c -o "$out/render$s.o" \
        "$rt/src/octree_render.c"
    run gcc -O2 -g -std=c99 -Wall -Wextra -I"$rt/include" -I"$rt/front/host" -o "$out/frames$s" tests/bench/callgrind_frames.c \
        "$out"/bunny00_d8/*.c "$out/render$s.o" "${others[@]}" -lm
    run valgrind --tool=callgrind --toggle-collect=mc_octree_render --callgrind-out-file="$out/cg$s.out" \
        "$out/frames$s" 20 --size "$size" >"$out/cg$s.txt" 2>"$out/cg$s.log"
done
"$out/frames0" 20 --size "$size" --ppm "$out/f0.ppm" >/dev/null
"$out/frames1" 20 --size "$size" --ppm "$out/f1.ppm" >/dev/null
cmp -s "$out/f0.ppm" "$out/f1.ppm" && same=yes || same=no
: >"$out/times.txt"
for r in $(seq 1 "$rounds"); do
    order="0 1"; [ $((r % 2)) = 0 ] && order="1 0"
    for s in $order; do
        "$out/frames$s" --time "$frames" --size "$size" | sed -n 's/^cpu ms per frame (median): //p' >"$out/t$s.txt"
    done
    echo "$(cat "$out/t0.txt") $(cat "$out/t1.txt")" >>"$out/times.txt"
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$same" "$load" "$size" "$frames" "$rounds" "$runtime_from" >"$out/section.md" <<'PY'
import statistics, sys
out, same, load, size, frames, rounds, runtime_from = sys.argv[1:8]
sys.path.insert(0, "tests/bench")
from bench_tools import ir_per_point, rounds as read_rounds
ir = lambda s: ir_per_point(f"{out}/cg{s}.log", f"{out}/cg{s}.txt")
rows, med = read_rounds(f"{out}/times.txt")
ratio = statistics.median(r[1] / r[0] for r in rows)
ir0, ir1 = ir(0), ir(1)
print("## Squares: a loop per level d-1 node or a mask per level d-2 node\n")
print(f"`tests/bench/flat_squares.sh` (`make bench`): bunny00 at depth 8, {size} (leaves two pixels across: "
      f"orthographic 2x2 squares), `callgrind_frames` (mc_clear + mc_octree_render, no finishing) built with the "
      f"runtime ({runtime_from}) compiled `-DMC_FLAT_SQUARES=0` (each level d-1 node's leaves in their own loop) and `=1` "
      f"(a level d-2 node's leaves as one 64-bit mask, the default on x86-64); {rounds} rounds of the {frames}-frame turn, "
      f"the two alternately; CPU ms = median over rounds of each round's median. Instructions: callgrind, 20-view turn, "
      f"mc_octree_render only. Same pixels in both builds: **{same}**.\n")
print("| walk | Ir per drawn point | CPU ms per frame |")
print("|---|---:|---:|")
print(f"| a loop per level d-1 node (MC_FLAT_SQUARES 0) | {ir0:.2f} | {med(0):.3f} |")
print(f"| a mask per level d-2 node (MC_FLAT_SQUARES 1, default on x86-64) | {ir1:.2f} | {med(1):.3f} |")
print()
print(f"The mask: **{ir1 / ir0:.2f}** times the instructions and **{ratio:.2f}** times the CPU time of a frame "
      f"(median over rounds of the ratio in each round).\n")
print("Per round (loop / mask ms): " + "; ".join(" / ".join(f"{v:.3f}" for v in r) for r in rows) + ".")
print(f"Load average at the end: {load}.")
PY
write_section "$results" flat "$out/section.md" "${cmds[@]}" \
    "$out/frames0 --time $frames --size $size; $out/frames1 --time $frames --size $size   # per round, alternately"
