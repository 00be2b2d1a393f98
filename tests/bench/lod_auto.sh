#!/usr/bin/env bash
# The automatic level of detail against a frame-time target: the viewer's --lod auto --target-ms T
# (runtime/front/host/lod_auto.h: the level kept while its frames are within 6 % of the target, else
# moved in one change to the face budget a power law through the last two levels' times predicts
# meets it; the change timed apart from the frame) over a full turn, per
# style and target: the median frame time and the frames within 10 % of the target after the first
# 20. A target is a share of the style's full-level median time in the same run, the least of three
# runs' (a target above that is met by drawing everything, and holds nothing). The line style's targets are run twice, one
# after the other: by the viewer of a plain bake and by that of a bake keeping the level's neighbour
# table (--mesh-neighbours), whose coarse levels cost less and whose level changes cost more.
# Writes a marked section of RESULTS.md.
#   tests/bench/lod_auto.sh [RESULTS.md]        (make bench runs it; make bench-lod-auto alone)
#   AUTO_MODEL (bunny00), AUTO_FRAMES (300), AUTO_TARGETS ("shaded:0.3 shaded:0.6 shaded:0.9 lines:0.7
#   lines:0.8 lines:0.9": style:share of its full level's median ms)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
model=${AUTO_MODEL:-bunny00} frames=${AUTO_FRAMES:-300}
targets=${AUTO_TARGETS:-shaded:0.3 shaded:0.6 shaded:0.9 lines:0.7 lines:0.8 lines:0.9}
out=build/bench/lod_auto
name=${model}_auto
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
src=build/models/$model.off
[ -f "$src" ] || make -s "$src"
run make -s view MODEL="$src" NAME="$name" BAKE_OPTS="--as both" >"$out/build.log"
run make -s view MODEL="$src" NAME="${name}_nbr" BAKE_OPTS="--as both --mesh-neighbours" >>"$out/build.log"
: >"$out/rows.txt"
rm -f "$out"/*-full.txt "$out"/*-full-[123].txt
for st in $targets; do
    style=${st%%:*} share=${st#*:}
    view=build/$name/$name-view
    # the style's full level first (once), whose median time the targets are shares of: the least of
    # three runs' medians (one slow run would put 0.9 of it above what the full level takes, a
    # target no level holds)
    if [ ! -f "$out/$style-full.txt" ]; then
        for k in 1 2 3; do run "$view" --mode "$style" --bench "$frames" >"$out/$style-full-$k.txt"; done
        least=$(for k in 1 2 3; do echo "$(sed -n 's/^ms per frame (median): //p' "$out/$style-full-$k.txt") $k"; done |
            sort -g | head -n 1 | cut -d' ' -f2)
        cp "$out/$style-full-$least.txt" "$out/$style-full.txt"
    fi
    full=$(sed -n 's/^ms per frame (median): //p' "$out/$style-full.txt")
    t=$(python3 -c "print(round($share * $full, 3))")
    bakes=plain
    [ "$style" = shaded ] || bakes="plain table"
    for b in $bakes; do
        v=$view
        [ "$b" = table ] && v=build/${name}_nbr/${name}_nbr-view
        run "$v" --mode "$style" --lod auto --target-ms "$t" --bench "$frames" >"$out/$style-$b-$t.txt"
        echo "$style $b $t $share" >>"$out/rows.txt"
    done
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$model" "$frames" "$load" >"$out/section.md" <<'PY'
import json, re, sys
out, model, frames, load = sys.argv[1:5]
print("## Automatic level of detail: holding a frame-time target\n")
print(f"`tests/bench/lod_auto.sh` (`make bench`, `make bench-lod-auto`): {model} baked `--as both`, the viewer's "
      f"`--bench {frames}` (a full turn, 320x240) with `--lod auto --target-ms T` (runtime/front/host/lod_auto.h): the "
      "level is kept while its time per frame (a moving average about three frames deep) is within 6 % of the target, "
      "and otherwise moved in one change to the finest level within the face budget that a power law t ~ F^e through "
      "the times of the current and the last level predicts meets the target (`mc_pmesh_lod_fit`; e learned as the "
      "levels change): a level change in the line styles costs far more than its splits (the crease bits brought over "
      "or recomputed), so it is made seldom, and it is timed apart from the frames, which teach the level's time. "
      "Held: frames after the first 20 whose time is within 10 % of the target. Each target is a share of the style's "
      "full-level median time in the same run, the least of three runs' (a target above that is met by drawing "
      "everything, and holds nothing). The lines targets "
      "twice, one run after the other: the plain bake's viewer, and that of the same bake with `--mesh-neighbours` "
      "(neighbour table: the level's neighbours kept in RAM, so coarse levels draw their lines without walking across "
      "removed faces, and every level change keeps the table).\n")
print("| style | bake | target ms (share of the full level's) | median ms | frames held within 10 % | level at the end (vertices) | full level's median ms |")
print("|---|---|---:|---:|---:|---:|---:|")
for line in open(f"{out}/rows.txt"):
    style, bake, t, share = line.split()
    a = open(f"{out}/{style}-{bake}-{t}.txt").read()
    full = open(f"{out}/{style}-full.txt").read()
    med = float(re.search(r"ms per frame \(median\): ([\d.]+)", a).group(1))
    held, n = map(int, re.search(r"(\d+) of (\d+) frames after the first 20 within 10 %", a).groups())
    level = int(re.search(r"lod (\d+) of \d+ vertices", a).group(1))
    fmed = float(re.search(r"ms per frame \(median\): ([\d.]+)", full).group(1))
    bake = "neighbour table" if bake == "table" else "plain"
    print(f"| {style} | {bake} | {float(t):g} ({float(share):g}) | {med:.3f} | {held} of {n} ({100 * held / n:.0f} %) | {level:,} | {fmed:.3f} |")
print(f"\nLoad average at the end: {load}.")
PY
write_section "$results" lod-auto "$out/section.md" "${cmds[@]}"
