#!/usr/bin/env bash
# The hot loop's depth test as a branch (MC_DEPTH_SELECT 0) and as a select (1, the default on x86-64), side by
# side with Mesa in one run: CPU ms per frame (median of rounds, each round branch / select / Mesa on
# the same 200-frame turn) and callgrind instructions per drawn point. Appends (replacing an earlier copy)
# a marked section to RESULTS.md. Run by tests/bench/run.sh after its own bakes (make bench):
#   tests/bench/depth_select.sh RESULTS.md [RUNTIME_DIR]
# Needs build/bench/bunny00_d8/ and build/bench/bin/bunny00_d8-osmesa from run.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh   # write_section
results=${1:-tests/bench/RESULTS.md}
rt=${2:-runtime}
d=${SELECT_DEPTH:-8} rounds=${SELECT_ROUNDS:-5} frames=${SELECT_FRAMES:-200} size=${BENCH_SIZE:-320x240}
name=bunny00_d$d
bake=build/bench/$name mesa=build/bench/bin/$name-osmesa out=build/bench/select
[ -d "$bake" ] && [ -x "$mesa" ] || { echo "depth_select: run tests/bench/run.sh first ($bake, $mesa)" >&2; exit 1; }
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
for s in 0 1; do
    run gcc -O2 -g -std=c99 -ffreestanding -Wall -Wextra -DMC_DEPTH_SELECT=$s -I"$rt/include" -c -o "$out/render$s.o" "$rt/src/octree_render.c"
    others=()
    for f in "$rt"/src/*.c; do [ "$(basename "$f")" = octree_render.c ] || others+=("$f"); done
    run gcc -O2 -g -std=c99 -Wall -Wextra -I"$rt/include" -I"$rt/front/host" -o "$out/frames$s" tests/bench/callgrind_frames.c \
        "$bake"/*.c "$out/render$s.o" "${others[@]}" -lm
    run valgrind --tool=callgrind --toggle-collect=mc_octree_render --callgrind-out-file="$out/cg$s.out" \
        "$out/frames$s" 20 --size "$size" >"$out/cg$s.txt" 2>"$out/cg$s.log"
done
cmp -s <("$out/frames0" 20 --size "$size" --ppm "$out/f0.ppm") <("$out/frames1" 20 --size "$size" --ppm "$out/f1.ppm") &&
    cmp -s "$out/f0.ppm" "$out/f1.ppm" && same=yes || same=no
: >"$out/times.txt"
for r in $(seq 1 "$rounds"); do
    b=$("$out/frames0" --time "$frames" --size "$size" | sed -n 's/^cpu ms per frame (median): //p')
    s=$("$out/frames1" --time "$frames" --size "$size" | sed -n 's/^cpu ms per frame (median): //p')
    m=$(env LP_NUM_THREADS=0 "$mesa" --frames "$frames" --views 0 --size "$size" | sed -n 's/^cpu ms per frame (median): //p')
    echo "$b $s $m" >>"$out/times.txt"
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$same" "$load" "$d" "$size" "$frames" "$rounds" >"$out/section.md" <<'PY'
import statistics, sys
out, same, load, d, size, frames, rounds = sys.argv[1:8]
sys.path.insert(0, "tests/bench")
from bench_tools import ir_per_point, rounds as read_rounds
ir = lambda s: ir_per_point(f"{out}/cg{s}.log", f"{out}/cg{s}.txt")
rows, med = read_rounds(f"{out}/times.txt")
ratio = lambda k: statistics.median(r[2] / r[k] for r in rows)
ir0, ir1 = ir(0), ir(1)
print("## Depth test: branch or select\n")
print(f"`tests/bench/depth_select.sh` (`make bench`): bunny00 at depth {d}, {size}, the {frames}-frame turn of section 1, "
      f"`callgrind_frames --time` (mc_clear + mc_octree_render, no finishing) with the runtime built with `-DMC_DEPTH_SELECT=0` "
      f"(a branch per leaf) and `=1` (a conditional move of the written pixel's index, the default on x86-64), and Mesa as in section 3; {rounds} rounds of "
      f"branch, select, Mesa; CPU ms = median over rounds of each round's median. Instructions: callgrind, 20-view turn, "
      f"mc_octree_render only. Same pixels in both builds: **{same}**.\n")
print("| depth test | Ir per drawn point | CPU ms per frame | Mesa CPU ms | ratio (median over rounds) |")
print("|---|---:|---:|---:|---:|")
print(f"| branch (MC_DEPTH_SELECT 0) | {ir0:.2f} | {med(0):.3f} | {med(2):.3f} | {ratio(0):.1f}x |")
print(f"| select (MC_DEPTH_SELECT 1, default on x86-64) | {ir1:.2f} | {med(1):.3f} | {med(2):.3f} | {ratio(1):.1f}x |")
print()
print("Per round (branch / select / Mesa ms): " + "; ".join(" / ".join(f"{v:.3f}" for v in r) for r in rows) + ".")
print(f"Load average at the end: {load}.")
PY
write_section "$results" select "$out/section.md" "${cmds[@]}" \
    "$out/frames0 --time $frames --size $size  # and frames1, and LP_NUM_THREADS=0 $mesa --frames $frames --views 0 --size $size, per round"
